"""What a compiled MuJoCo model says besides its tree: loops, couplings, springs and actuators.

- `<equality>` `connect` -> a spherical cut whose frames sit at the point on each body: the anchor on
  body 1 and where it is on body 2 at qpos0 (MuJoCo's anchor on body 2), or the two sites (`site1`,
  `site2`, MuJoCo 3's form); two `connect`s between the same two bodies (either form, either order) at
  distinct points, as many points apart on each body -> one revolute cut about the line through them
  (onshape-to-robot writes a hinge closure so); `weld` -> a weld cut (as MuJoCo's: the point at
  relpose's position on body 1 meets the anchor on body 2, whose frame is turned by relpose's
  rotation from body 1's; relpose is the qpos0 pose when the file gives none); on sites: the site
  frames meet. `joint` -> a `Coupling` (joint1 - its qpos0 = polycoef(joint2 - its qpos0));
  `tendon` (fixed tendons) -> a `Coupling` of the tendon lengths about their qpos0 lengths.
- joint `stiffness`, `springref` (MuJoCo's qpos_spring) and `damping` -> `JointSpring`s (none where
  `<flag spring="disable">` / `damper="disable"`); a ball or free joint carries damping only.
- actuators on a hinge or slide -> that joint is actuated (the effort is the joint's generalised
  force: MuJoCo's gear is not applied); on a fixed tendon -> an `Actuator` whose joint coefficients
  are the tendon's times the gear (the effort is MuJoCo's actuator force).

Spatial tendons between two sites, their springs and dampers and the actuators on them are forces
(`mechkit.sources.mjcf.spatial_tendons`). Refused by name: inactive equalities aside, every other
equality kind (flex, distance), equalities on spatial tendons, actuators on sites, bodies or
slider-cranks, fixed tendons' springs, dampers and armature, ball-joint stiffness, nonlinear
(polynomial) joint stiffness or damping. Not read: contacts, limits, friction loss, actuator dynamics and
gains, solver parameters.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import MalformedDescription
from mechkit.core import Actuator, Coupling, JointSpring, LoopClosure
from mechkit.sources.mjcf.spatial_tendons import spatial
from mechkit.sources.mjcf.tree import Tree, se3
from mechkit.sources.pinocchio_tree import add_frame

if TYPE_CHECKING:
    from mujoco import MjModel

CONNECT, WELD, JOINT, TENDON = 0, 1, 2, 3  # mjtEq
OBJ_SITE = 6  # mjtObj
TRN_JOINT, TRN_JOINTINPARENT, TRN_TENDON = 0, 1, 3  # mjtTrn
WRAP_JOINT = 1  # mjtWrap
ONE_FREEDOM = (2, 3)  # mjtJoint: slide, hinge
SPRING_OFF, DAMPER_OFF = 1 << 5, 1 << 6  # mjtDisableBit: <flag spring="disable">, <flag damper="disable">


def equalities(mm: MjModel, tree: Tree) -> tuple[tuple[LoopClosure, ...], tuple[Coupling, ...]]:
    """The loops (their frames added to `tree.model`) and couplings of the active equalities.

    Args:
        mm: the compiled MuJoCo model.
        tree: its Pinocchio tree (`build_tree`).

    Returns:
        (the loop closures, the joint couplings).

    Raises:
        MalformedDescription: an equality kind or object mechkit does not read (named).
    """
    closures: list[LoopClosure] = []
    couplings: list[Coupling] = []
    connects: dict[tuple[int, int], list[tuple[str, np.ndarray, np.ndarray]]] = {}
    for e in range(mm.neq):
        if not mm.eq_active0[e]:
            continue
        name, kind, data = tree.names["equality"][e], int(mm.eq_type[e]), np.asarray(mm.eq_data[e], dtype=float)
        o1, o2 = int(mm.eq_obj1id[e]), int(mm.eq_obj2id[e])
        where = f"MJCF equality {name!r}"
        if kind == WELD and int(mm.eq_objtype[e]) == OBJ_SITE:
            a = se3(mm.site_quat[o1], mm.site_pos[o1])
            b = se3(mm.site_quat[o2], mm.site_pos[o2])
            closures.append(_cut(tree, name, "weld", int(mm.site_bodyid[o1]), int(mm.site_bodyid[o2]), a, b))
        elif kind == CONNECT:
            if int(mm.eq_objtype[e]) == OBJ_SITE:
                p1, p2 = (np.asarray(mm.site_pos[o], dtype=float) for o in (o1, o2))
                o1, o2 = int(mm.site_bodyid[o1]), int(mm.site_bodyid[o2])
            else:
                p1 = data[0:3]
                p2 = tree.world[o2].actInv(tree.world[o1].act(p1))
            if (o2, o1) in connects:  # the same two bodies, named the other way round
                o1, o2, p1, p2 = o2, o1, p2, p1
            connects.setdefault((o1, o2), []).append((name, p1, p2))
        elif kind == WELD:  # MuJoCo's weld: relpose's point on body 1 meets the anchor on body 2, which is
            # turned by relpose's rotation from body 1
            closures.append(_cut(tree, name, "weld", o1, o2, se3(data[6:10], data[3:6]), pin.SE3(np.eye(3), data[0:3])))
        elif kind == JOINT:
            couplings.append(_joint_coupling(mm, tree, name, o1, o2, data))
        elif kind == TENDON:
            first = fixed_tendon(mm, tree, o1, where)
            second = fixed_tendon(mm, tree, o2, where) if o2 >= 0 else ()
            couplings.append(
                Coupling(
                    name,
                    first,
                    second,
                    tuple(float(c) for c in data[0:5]),
                    float(mm.tendon_length0[o1]),
                    float(mm.tendon_length0[o2]) if o2 >= 0 else 0.0,
                )
            )
        else:
            raise MalformedDescription(where, "only connect, weld, joint and tendon equalities are read")
    for (b1, b2), anchors in connects.items():
        closures += _connects(tree, b1, b2, anchors)
    return tuple(closures), tuple(couplings)


def _connects(tree: Tree, b1: int, b2: int, points: list) -> list[LoopClosure]:
    """Cuts of the connects between two bodies, each (name, point on b1, point on b2): a revolute one
    per pair at distinct points, about the line through them, else spherical. Frame a is at the point on
    b1, turned as b1; frame b at the point on b2, turned as frame a at qpos0 but for the least rotation
    that takes the line on b1 onto the line on b2 (none when the connects are closed at qpos0)."""
    out = []
    relative = (tree.world[b2].inverse() * tree.world[b1]).rotation
    while points:
        name, p1, p2 = points.pop(0)
        other = next((c for c in points if np.linalg.norm(c[1] - p1) > 1e-9), None)
        R, axis = relative, None
        if other is not None:
            points.remove(other)
            d1, d2 = other[1] - p1, other[2] - p2
            if abs(np.linalg.norm(d1) - np.linalg.norm(d2)) > 1e-9 * max(1.0, np.linalg.norm(d1)):
                raise MalformedDescription(
                    f"MJCF equalities {name!r} and {other[0]!r}",
                    f"connect the same two bodies at points {np.linalg.norm(d1):.9g} m apart on "
                    f"{tree.names['body'][b1]!r} but {np.linalg.norm(d2):.9g} m apart on "
                    f"{tree.names['body'][b2]!r}: no pose satisfies both",
                )
            axis = d1 / np.linalg.norm(d1)
            R = _turning(R @ axis, d2 / np.linalg.norm(d2)) @ R
        out.append(
            _cut(
                tree,
                name,
                "spherical" if other is None else "revolute",
                b1,
                b2,
                pin.SE3(np.eye(3), p1),
                pin.SE3(R, p2),
                axis,
            )
        )
    return out


def _turning(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The least rotation taking unit vector u onto unit vector v (a half turn about an axis normal to u
    when they are opposite)."""
    w, c = np.cross(u, v), float(u @ v)
    if c < -1 + 1e-12:
        normal = np.cross(u, np.eye(3)[int(np.argmin(np.abs(u)))])
        return pin.exp3(np.pi * normal / np.linalg.norm(normal))
    return pin.exp3(w / max(np.linalg.norm(w), 1e-300) * np.arctan2(np.linalg.norm(w), c))


def _cut(tree: Tree, name: str, kind: str, b1: int, b2: int, a: pin.SE3, b: pin.SE3, axis=None) -> LoopClosure:
    """A cut whose frames `<name>_a`, `<name>_b` sit at `a` in body b1's frame and `b` in body b2's."""
    if b1 == b2:
        raise MalformedDescription(f"MJCF equality {name!r}", "both sides are on one body")
    for frame, body, at in ((f"{name}_a", b1, a), (f"{name}_b", b2, b)):
        add_frame(tree.model, frame, tree.body_joint[body], tree.body_placement[body] * at)
    return LoopClosure(name, kind, f"{name}_a", f"{name}_b", axis, explicit_rows=False)


def _joint_coupling(mm: MjModel, tree: Tree, name: str, j1: int, j2: int, data: np.ndarray) -> Coupling:
    """joint1 - qpos0 = polycoef(joint2 - qpos0) (joint1 held at qpos0 + polycoef[0] without joint2; MuJoCo
    allows hinges and slides only)."""
    leader = ((tree.names["joint"][j2], 1.0),) if j2 >= 0 else ()
    ref = float(mm.qpos0[mm.jnt_qposadr[j2]]) if j2 >= 0 else 0.0
    return Coupling(
        name,
        ((tree.names["joint"][j1], 1.0),),
        leader,
        tuple(float(c) for c in data[0:5]),
        float(mm.qpos0[mm.jnt_qposadr[j1]]),
        ref,
    )


def fixed_tendon(mm: MjModel, tree: Tree, t: int, where: str) -> tuple[tuple[str, float], ...]:
    """A fixed tendon as ((joint, coefficient), ...): its length is the sum of coefficient * joint value
    (MuJoCo allows hinges and slides only).

    Args:
        mm: the compiled MuJoCo model.
        tree: its Pinocchio tree (`build_tree`).
        t: the tendon's MuJoCo id.
        where: what uses it, for the error.

    Returns:
        (joint, coefficient) terms; the length in m or rad.

    Raises:
        MalformedDescription: a spatial tendon.
    """
    terms = []
    for w in range(int(mm.tendon_adr[t]), int(mm.tendon_adr[t]) + int(mm.tendon_num[t])):
        if int(mm.wrap_type[w]) != WRAP_JOINT:
            raise MalformedDescription(
                where,
                f"tendon {tree.names['tendon'][t]!r} is spatial: only fixed tendons (sums of joint values) are read",
            )
        terms.append((tree.names["joint"][int(mm.wrap_objid[w])], float(mm.wrap_prm[w])))
    return tuple(terms)


def check_tendons(mm: MjModel, tree: Tree) -> None:
    """Refuse tendon springs, dampers, armature and friction loss, which no record carries.

    Args:
        mm: the compiled MuJoCo model.
        tree: its Pinocchio tree (`build_tree`).

    Raises:
        MalformedDescription: a tendon with any of them.
    """
    for t in range(mm.ntendon):
        if spatial(mm, t):
            continue  # its spring and damper: `spatial_tendons`
        for field in ("tendon_stiffness", "tendon_damping", "tendon_armature", "tendon_frictionloss"):
            if np.any(np.asarray(getattr(mm, field)[t]) != 0):
                raise MalformedDescription(
                    f"MJCF tendon {tree.names['tendon'][t]!r}",
                    f"{field.removeprefix('tendon_')} on a tendon is not read",
                )


def springs(mm: MjModel, tree: Tree) -> tuple[JointSpring, ...]:
    """Joint springs and dampers (stiffness N m/rad or N/m, springref, damping N m s/rad or N s/m).

    Args:
        mm: the compiled MuJoCo model.
        tree: its Pinocchio tree (`build_tree`).

    Returns:
        The joint springs (MuJoCo's springref is the reference, no preload).

    Raises:
        MalformedDescription: polynomial stiffness or damping, a ball or free joint with stiffness,
            or with different damping on its freedoms.
    """
    out = []
    for j, name in enumerate(tree.names["joint"]):
        dof, kind = int(mm.jnt_dofadr[j]), int(mm.jnt_type[j])
        nv = 1 if kind in ONE_FREEDOM else (3 if kind == 1 else 6)
        damping = np.asarray(mm.dof_damping[dof : dof + nv], dtype=float) * (not mm.opt.disableflags & DAMPER_OFF)
        stiffness = float(mm.jnt_stiffness[j]) * (not mm.opt.disableflags & SPRING_OFF)
        if np.any(mm.jnt_stiffnesspoly[j] != 0) or np.any(mm.dof_dampingpoly[dof : dof + nv] != 0):
            raise MalformedDescription(
                f"MJCF joint {name!r}", "polynomial (nonlinear) stiffness or damping is not read"
            )
        if kind not in ONE_FREEDOM and (stiffness != 0 or np.ptp(damping) != 0):
            raise MalformedDescription(
                f"MJCF joint {name!r}",
                "a ball or free joint's stiffness (or unequal damping on its freedoms) is not read",
            )
        if stiffness != 0 or damping[0] != 0:
            reference = float(mm.qpos_spring[mm.jnt_qposadr[j]]) if kind in ONE_FREEDOM else 0.0
            out.append(JointSpring(name, stiffness, reference, 0.0, float(damping[0])))
    return tuple(out)


def actuation(mm: MjModel, tree: Tree) -> tuple[tuple[str, ...], tuple[Actuator, ...]]:
    """(actuated names in effort order, tendon actuators): see the module docstring.

    Args:
        mm: the compiled MuJoCo model.
        tree: its Pinocchio tree (`build_tree`).

    Returns:
        (actuated joint or tendon names in effort order, tendon actuators).

    Raises:
        MalformedDescription: an actuator on a ball or free joint, a site, a body or
            a slider-crank; two actuators on one joint; a tendon actuator named like a joint.
    """
    actuated: list[str] = []
    actuators: list[Actuator] = []
    for u, name in enumerate(tree.names["actuator"]):
        where, trn, target = f"MJCF actuator {name!r}", int(mm.actuator_trntype[u]), int(mm.actuator_trnid[u][0])
        gear = float(mm.actuator_gear[u][0])
        if trn in (TRN_JOINT, TRN_JOINTINPARENT):
            joint = tree.names["joint"][target]
            if int(mm.jnt_type[target]) not in ONE_FREEDOM:
                raise MalformedDescription(where, f"drives the ball or free joint {joint!r}: not read")
            if joint in actuated:
                raise MalformedDescription(where, f"joint {joint!r} is driven by another actuator already")
            actuated.append(joint)
        elif trn == TRN_TENDON and spatial(mm, target):
            continue  # a force along the tendon: `spatial_tendons`
        elif trn == TRN_TENDON:
            if name in tree.names["joint"]:
                raise MalformedDescription(where, "a tendon actuator named like a joint: rename one of them")
            terms = fixed_tendon(mm, tree, target, where)
            actuators.append(Actuator(name, tuple((joint, gear * c) for joint, c in terms)))
            actuated.append(name)
        else:
            raise MalformedDescription(
                where, "acts on a site, a body or a slider-crank: only joint and fixed-tendon transmissions are read"
            )
    return tuple(actuated), tuple(actuators)
