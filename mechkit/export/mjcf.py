"""MJCF (MuJoCo) export of a mechanism: the tree, its geoms, limits, springs, motors and stiff closures.

One `<body>` per Pinocchio joint (its frame is the joint frame), `<inertial>` from the model (MuJoCo
then ignores the geoms' volume; a body whose mass or a principal moment is below MuJoCo's `mjMINVAL`,
a massless link, a rotor or a thin rod, has no counterpart and is refused by name), every URDF frame
as a `<site>`, and:

- geoms: the URDF visuals (box, cylinder, sphere) at their placements; a body with no primitive
  visual (none, or meshes only) gets a capsule from its joint to each child joint and cut frame.
  Contacts are off (`contype = conaffinity = 0`): the links of a mechanism overlap at its pins.
- joints: `range` from the URDF limits, `damping` from the URDF `<dynamics>`, and the stiffness,
  spring reference and damping of a `<mechkit:spring>` element (torque = preload - stiffness
  (q - reference) - damping qdot, so `springref` = reference + preload / stiffness).
- actuators: a `<motor>` per actuated joint (ctrl = joint effort, N m or N; `ctrlrange` from the
  URDF effort limit).
- closures as `<equality>` elements:

| cut kind / rows | MJCF |
|---|---|
| revolute, rows planar | one `connect` at the pin (3 rows; the out-of-plane one is redundant) |
| revolute, rows spatial or spherical | two `connect`s on the axis, `AXIS_ANCHOR_OFFSET` apart |
| spherical | one `connect` |
| weld | one `weld` |
| hooke, prismatic | none exists: `MethodUnavailable` |

Stiffness of the closures: MuJoCo's equality constraints are soft (a spring-damper of time constant
`solref[0]` and impedance `solimp`). The time scale of the model is its smallest link period
`T = 2 pi sqrt(I_axis / (m g r))` (each link a compound pendulum about its own joint axis, r the
distance of its centre of mass from the axis); the export writes `solref = (T / SOLREF_DIVISOR, 1)`
(critically damped), the impedance at `SOLIMP`, a timestep of `solref[0] / STEPS_PER_TIMECONST`
(MuJoCo needs at least 2) and the RK4 integrator, and says so in an XML comment. These choices are
ours: with them every registered mechanism, released at home under gravity with no effort, keeps
its loops closed within 1e-4 m over 1 s (worst measured 2.2e-5 m, the deployable mast; with
MuJoCo's semi-implicit Euler at the same step it drifts by 0.5 mm; tests/export/test_mjcf.py).

MuJoCo's `connect` (and Pinocchio's MJCF reader) take the second body's anchor from the
configuration in which the model is written, so the bodies are written at the assembled home
configuration, each joint with `ref` = its home value: MuJoCo's qpos then equals Pinocchio's q
(same joint order, same zero). Gravity: the model's (-9.81 m/s^2 along world z).
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from typing import TYPE_CHECKING

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import MethodUnavailable
from mechkit.core import AXIS_ANCHOR_OFFSET, body_name
from mechkit.export.urdf import linear_coupling, source_text
from mechkit.export.xmltext import numbers as _fmt
from mechkit.export.xmltext import quat_wxyz as _quat_wxyz

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

#: Name of the fixed MJCF body that carries the ground side of the mechanism.
ROOT_BODY = "ground"
#: solref time constant = smallest link period / SOLREF_DIVISOR (ours).
SOLREF_DIVISOR = 600.0
#: timestep = solref time constant / STEPS_PER_TIMECONST (ours; MuJoCo requires >= 2).
STEPS_PER_TIMECONST = 3.0
#: Equality impedance (dmin, dmax, width, midpoint, power): near MuJoCo's cap, so that the
#: constraint is nearly hard (ours).
SOLIMP = (0.9999, 0.9999, 0.001, 0.5, 2.0)
#: Period used when no link swings under gravity (s, ours).
DEFAULT_PERIOD = 1.0
#: Radius of the capsules drawn along links without a primitive visual (m, ours).
CAPSULE_RADIUS = 0.005


def _joint_kind(model: pin.Model, joint: int) -> tuple[str, np.ndarray]:
    """MJCF joint type and axis (joint frame) of a one-coordinate Pinocchio joint."""
    jm = model.joints[joint]
    short = jm.shortname()
    if model.nqs[joint] != 1 or model.nvs[joint] != 1:
        raise MethodUnavailable(
            "mjcf export",
            f"joint {model.names[joint]!r} ({short}) has {model.nqs[joint]} coordinates; "
            "only one-coordinate revolute and prismatic joints are exported",
        )
    for kind, prefix in (("hinge", "JointModelR"), ("slide", "JointModelP")):
        if short.startswith(prefix):
            if short[len(prefix) :] in ("X", "Y", "Z"):
                return kind, np.eye(3)["XYZ".index(short[-1])]
            return kind, np.asarray(jm.extract().axis, dtype=float)
    raise MethodUnavailable("mjcf export", f"joint {model.names[joint]!r} is {short}")


def smallest_link_period(model: pin.Model) -> float:
    """Smallest small-swing period (s) of a link as a compound pendulum about its own hinge axis.

    T = 2 pi sqrt(I_axis / (m g r)), with I_axis the link's inertia about its joint axis (kg m^2)
    and r the distance of its centre of mass from that axis (m); links that do not swing under
    gravity (slides, centre of mass on the axis) are skipped. `DEFAULT_PERIOD` when none swings.

    Args:
        model: the Pinocchio model (its gravity and inertias).

    Returns:
        The period (s).
    """
    g = float(np.linalg.norm(model.gravity.linear))
    periods = []
    for j in range(1, model.njoints):
        inertia = model.inertias[j]
        if inertia.mass <= 0 or not model.joints[j].shortname().startswith("JointModelR") or g == 0:
            continue
        _, axis = _joint_kind(model, j)
        c = inertia.lever
        r = float(np.linalg.norm(c - axis * (axis @ c)))
        if r < 1e-9:
            continue
        i_axis = float(axis @ inertia.inertia @ axis) + inertia.mass * r**2
        periods.append(2 * math.pi * math.sqrt(i_axis / (inertia.mass * g * r)))
    return min(periods, default=DEFAULT_PERIOD)


def _equalities(mech: Mechanism, names: dict[int, str], solref: str) -> list[tuple[str, dict[str, str]]]:
    """MJCF equality elements (tag, attributes) of the closures."""
    model = mech.model
    out = []
    stiff = {"solref": solref, "solimp": _fmt(SOLIMP)}
    for cut in mech.cuts:
        c = cut.closure
        fa, fb = model.frames[cut.frame_a], model.frames[cut.frame_b]
        body1, body2 = names[fa.parentJoint], names[fb.parentJoint]
        if c.kind == "weld":
            out.append(("weld", {"name": c.name, "body1": body1, "body2": body2, **stiff}))
            continue
        if c.kind in ("hooke", "prismatic"):
            raise MethodUnavailable(
                "mjcf export", f"cut {c.name!r} is {c.kind}: MuJoCo has no equality constraint for it"
            )
        offsets = [np.zeros(3)]
        if c.kind == "revolute" and c.rows != "planar":
            offsets.append(AXIS_ANCHOR_OFFSET * c.axis)
        for k, offset in enumerate(offsets):
            anchor = fa.placement.act(offset)
            out.append(
                (
                    "connect",
                    {
                        "name": f"{c.name}" + (f"_{k}" if k else ""),
                        "body1": body1,
                        "body2": body2,
                        "anchor": _fmt(anchor),
                        **stiff,
                    },
                )
            )
    return out


def springs(mech: Mechanism) -> dict[str, tuple[float, float, float]]:
    """The mechanism's joint springs, as MJCF writes them.

    Args:
        mech: the mechanism.

    Returns:
        Joint -> (stiffness (N m/rad or N/m), spring reference (rad or m: where the spring's effort vanishes,
            reference + preload / stiffness), damping (N m s/rad or N s/m)).
    """
    return {
        s.joint: (s.stiffness, s.reference + s.preload / s.stiffness if s.stiffness else s.reference, s.damping)
        for s in mech.springs.springs
    }


#: MuJoCo's smallest mass (kg) and principal moment (kg m^2) of a moving body (mjMINVAL).
MJMINVAL = 1e-15


def _visual_geoms(mech: Mechanism) -> list[tuple[int, str, dict[str, str]]]:
    """(joint, name, attributes) of the URDF's primitive visuals; none when they cannot be read."""
    try:
        geometry = pin.buildGeomFromUrdfString(mech.model, source_text(mech, "mjcf export"), pin.GeometryType.VISUAL)
    except (RuntimeError, ValueError):  # mesh files that cannot be found: capsules instead
        return []
    out = []
    for obj in geometry.geometryObjects:
        shape = obj.geometry
        kind = type(shape).__name__
        if kind == "Box":
            attrs = {"type": "box", "size": _fmt(shape.halfSide)}
        elif kind == "Cylinder":
            attrs = {"type": "cylinder", "size": _fmt([shape.radius, shape.halfLength])}
        elif kind == "Sphere":
            attrs = {"type": "sphere", "size": _fmt([shape.radius])}
        else:
            continue
        M = obj.placement
        attrs.update(pos=_fmt(M.translation), quat=_fmt(_quat_wxyz(M.rotation)))
        rgba = np.asarray(obj.meshColor, dtype=float)
        if rgba.size == 4 and np.all(rgba >= 0):
            attrs["rgba"] = _fmt(rgba)
        out.append((obj.parentJoint, obj.name, attrs))
    return out


def _capsule_ends(mech: Mechanism, joint: int) -> list[np.ndarray]:
    """Points (joint frame, m) a capsule joins to the joint's origin: child joints and cut frames."""
    model = mech.model
    ends = [model.jointPlacements[c].translation for c in range(1, model.njoints) if model.parents[c] == joint]
    for cut in mech.cuts:
        for f in (cut.frame_a, cut.frame_b):
            if model.frames[f].parentJoint == joint:
                ends.append(model.frames[f].placement.translation)
    return [e for e in ends if np.linalg.norm(e) > 1e-6]


def _add_geoms(mech: Mechanism, elements: dict[int, ET.Element]) -> None:
    """The visuals as contact-free geoms; capsules along links that have no primitive visual."""
    off = {"contype": "0", "conaffinity": "0", "group": "1"}
    drawn = set()
    for joint, name, attrs in _visual_geoms(mech):
        ET.SubElement(elements[joint], "geom", name=name, **attrs, **off)
        drawn.add(joint)
    for joint, element in elements.items():
        if joint in drawn:
            continue
        for k, end in enumerate(_capsule_ends(mech, joint)):
            ET.SubElement(
                element,
                "geom",
                name=f"{element.get('name', ROOT_BODY)}_capsule_{k}",
                type="capsule",
                size=_fmt([CAPSULE_RADIUS]),
                fromto=_fmt([*np.zeros(3), *end]),
                **off,
            )


def to_mjcf(mech: Mechanism, q: np.ndarray | None = None) -> str:
    """MJCF text of the mechanism, bodies written at q (default: the home assembly).

    Args:
        mech: the mechanism.
        q: configuration (nq,) the bodies are written at, closed (default `mech.home_q`).

    Returns:
        The MJCF text.

    Raises:
        MethodUnavailable: a joint, cut or body (massless, a rotor, a thin rod) with no MJCF counterpart.
        MalformedDescription: a `<mechkit:spring>` element that cannot be read.
    """
    model = mech.model
    q = mech.home_q if q is None else np.asarray(q, dtype=float)
    period = smallest_link_period(model)
    timeconst = period / SOLREF_DIVISOR
    solref = _fmt([timeconst, 1.0])
    root = ET.Element("mujoco", model=mech.spec.name)
    root.append(
        ET.Comment(
            f" closures: solref = ({timeconst:.6g} s, 1) = smallest link period {period:.6g} s / {SOLREF_DIVISOR:g}"
            f" (each link a compound pendulum about its joint), solimp {_fmt(SOLIMP)}, timestep = solref / "
            f"{STEPS_PER_TIMECONST:g}, integrator RK4 "
        )
    )
    ET.SubElement(root, "compiler", angle="radian", autolimits="true")
    ET.SubElement(
        root,
        "option",
        gravity=_fmt(model.gravity.linear),
        timestep=repr(timeconst / STEPS_PER_TIMECONST),
        integrator="RK4",
    )
    # one jointless root body holds every tree: Pinocchio's MJCF reader takes the first body only;
    # the ground's geoms go to the worldbody (Pinocchio asks a body with geoms for an inertia)
    worldbody = ET.SubElement(root, "worldbody")
    world = ET.SubElement(worldbody, "body", name=ROOT_BODY)
    names = {0: ROOT_BODY}
    elements = {0: world}
    spring = springs(mech)
    for j in range(1, model.njoints):
        kind, axis = _joint_kind(model, j)
        value = q[model.idx_qs[j]]
        motion = axis * value
        M = model.jointPlacements[j] * (
            pin.exp6(pin.Motion(np.zeros(3), motion)) if kind == "hinge" else pin.SE3(np.eye(3), motion)
        )
        names[j] = body_name(model, j)
        body = ET.SubElement(
            elements[model.parents[j]],
            "body",
            name=names[j],
            pos=_fmt(M.translation),
            quat=_fmt(_quat_wxyz(M.rotation)),
        )
        inertia = model.inertias[j]
        moments = np.linalg.eigvalsh(inertia.inertia)
        if inertia.mass < MJMINVAL or moments[0] < MJMINVAL:
            raise MethodUnavailable(
                "mjcf export",
                f"body {names[j]!r} has a mass of {inertia.mass:.6g} kg and principal "
                f"moments {_fmt(moments)} kg m^2: MuJoCo needs both above {MJMINVAL:g} for a moving "
                "body (a massless link, a rotor or a thin rod has no MJCF counterpart)",
            )
        if inertia.mass > 0:
            I = inertia.inertia
            full = [I[0, 0], I[1, 1], I[2, 2], I[0, 1], I[0, 2], I[1, 2]]
            ET.SubElement(
                body, "inertial", pos=_fmt(inertia.lever), mass=repr(float(inertia.mass)), fullinertia=_fmt(full)
            )
        attrs = {"name": model.names[j], "type": kind, "axis": _fmt(axis), "ref": repr(float(value))}
        iq, iv = model.idx_qs[j], model.idx_vs[j]
        lower, upper = model.lowerPositionLimit[iq], model.upperPositionLimit[iq]
        if np.isfinite(lower) and np.isfinite(upper) and lower < upper:
            attrs["range"] = _fmt([lower, upper])
        damping = float(model.damping[iv])
        if model.names[j] in spring:
            k, free, c = spring[model.names[j]]
            attrs.update(stiffness=repr(k), springref=repr(free))
            damping += c
        if damping > 0:
            attrs["damping"] = repr(damping)
        ET.SubElement(body, "joint", attrs)
        elements[j] = body
    _add_geoms(mech, {0: worldbody, **{j: e for j, e in elements.items() if j}})
    for frame in model.frames:
        if frame.type == pin.FrameType.BODY and not frame.placement.isIdentity():
            ET.SubElement(
                elements[frame.parentJoint],
                "site",
                name=frame.name,
                pos=_fmt(frame.placement.translation),
                quat=_fmt(_quat_wxyz(frame.placement.rotation)),
            )
    equality = ET.SubElement(root, "equality")
    for tag, attrs in _equalities(mech, names, solref):
        ET.SubElement(equality, tag, attrs)
    for coupling in mech.closure_model.couplings:  # joint1 - ref1 = a0 + a1 (joint2 - ref2): refs are the values at q
        follower, leader, multiplier, offset = linear_coupling(coupling, "mjcf export")
        x_f, x_l = (float(q[model.idx_qs[model.getJointId(j)]]) for j in (follower, leader))
        polycoef = _fmt([multiplier * x_l + offset - x_f, multiplier, 0.0, 0.0, 0.0])
        attrs = {"name": coupling.name, "joint1": follower, "joint2": leader, "polycoef": polycoef}
        ET.SubElement(equality, "joint", {**attrs, "solref": solref, "solimp": _fmt(SOLIMP)})
    actuator = ET.SubElement(root, "actuator")
    for joint in mech.actuated:
        effort = float(model.effortLimit[model.idx_vs[model.getJointId(joint)]])
        limits = {"ctrlrange": _fmt([-effort, effort])} if 0 < effort < np.inf else {}
        ET.SubElement(actuator, "motor", name=joint, joint=joint, **limits)
    ET.indent(root)
    return ET.tostring(root, encoding="unicode") + "\n"
