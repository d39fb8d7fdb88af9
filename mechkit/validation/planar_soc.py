"""SOC building blocks for planar linkages in the x-z plane (numpy only): virtual-displacement
Jacobians from the linkage's own geometry, body loads, pin sites, and two decompositions of a
single-loop linkage cut at "C" (the classic whole-mechanism SKC and a sequential one).

A body's "chain" lists, per virtual coordinate of its SKC, None (the coordinate does not move the
body), "x" / "z" (a translation) or a planar pivot (x, z) (a rotation about -y about that pivot).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechkit.validation.planar_motion import AXIS, LinkageState, LinkState, PlanarJoint, to_world
from mechkit.validation.soc import BodyLoad, SKCInstant, WrenchSite

Chain = tuple[Any, ...]


def point_jacobian(point: np.ndarray, chain: Chain) -> np.ndarray:
    """(6, n): virtual displacement (rows 0-2) and rotation (rows 3-5) of a body point, world.

    Args:
        point: the body point (2,), planar, m.
        chain: the body's virtual coordinates: "x", "z" (a translation) or a pivot (2,) (a rotation about it),
            None for a coordinate that does not move the body.

    Returns:
        (6, n) matrix, world axes, n = len(chain).
    """
    jac = np.zeros((6, len(chain)))
    for j, pivot in enumerate(chain):
        if isinstance(pivot, str):
            jac["xz".index(pivot) * 2, j] = 1.0
        elif pivot is not None:
            d = point - pivot
            jac[:3, j] = to_world(np.array([-d[1], d[0]]))
            jac[3:, j] = AXIS
    return jac


def body_load(link: LinkState, chain: Chain) -> BodyLoad:
    """The SOC body of a link moving along `chain`.

    Args:
        link: the link's motion.
        chain: the body's virtual coordinates: "x", "z" (a translation) or a pivot (2,) (a rotation about it),
            None for a coordinate that does not move the body.

    Returns:
        The body for the SOC solver.
    """
    jac = point_jacobian(link.com, chain)
    return BodyLoad(
        link.name,
        link.bar.mass,
        link.bar.inertia_world(link.angle),
        to_world(link.com_acceleration),
        link.omega * AXIS,
        link.alpha * AXIS,
        jac[:3],
        jac[3:],
    )


def pin_site(joint: str, point: np.ndarray, chain: Chain, sign: float) -> WrenchSite:
    """A pin of the x-z plane acting on the body of `chain`: in-plane forces (fx, fz) unknown or known.

    Args:
        joint: the pin's name.
        point: the pin's position (2,), m.
        chain: the body's virtual coordinates: "x", "z" (a translation) or a pivot (2,) (a rotation about it),
            None for a coordinate that does not move the body.
        sign: +1 where the body is the pin's child side, -1 where it is the parent side.

    Returns:
        The wrench site.
    """
    return WrenchSite(joint, point_jacobian(point, chain), sign, (0, 2))


def motor_column(chain: Chain) -> np.ndarray:
    """Generalised force of a unit motor torque about -y from the ground on the body of `chain`.

    Args:
        chain: the body's virtual coordinates: "x", "z" (a translation) or a pivot (2,) (a rotation about it),
            None for a coordinate that does not move the body.

    Returns:
        (n,) generalised force, n = len(chain).
    """
    return point_jacobian(np.zeros(2), chain)[3:].T @ AXIS


def free_chain(pivot: np.ndarray) -> Chain:
    """A body free in the plane: x, z and a rotation about `pivot`.

    Args:
        pivot: the rotation's pivot (2,), m.

    Returns:
        The chain ("x", "z", pivot).
    """
    return ("x", "z", pivot)


def subtree(state: LinkageState, link: str) -> list[str]:
    """`link` and every link hinged after it in the tree (the loop cut "C" excluded).

    Args:
        state: the linkage's state.
        link: a link's name.

    Returns:
        Link names.
    """
    children = [j.child for j in state.joints if j.parent == link and j.name != "C"]
    return [link] + [d for child in children for d in subtree(state, child)]


def whole_skc(state: LinkageState) -> SKCInstant:
    """Classic virtual work: the whole linkage over its URDF coordinates q, the cut "C" as loop rows.

    Args:
        state: the linkage's state.

    Returns:
        One SKC holding every body and motor.
    """
    n = len(state.coordinates)
    chains: dict[str, list[Any]] = {name: [None] * n for name in state.links}
    for j, name in enumerate(state.coordinates):
        joint = state.joint(name)
        for link in subtree(state, joint.child):
            chains[link][j] = joint.point
    cut = state.joint("C")
    loop = (point_jacobian(cut.point, tuple(chains[cut.parent])) - point_jacobian(cut.point, tuple(chains[cut.child])))[
        [0, 2]
    ]
    bodies = tuple(body_load(link, tuple(chains[name])) for name, link in state.links.items())
    motors = tuple((j.name, np.eye(n)[state.coordinates.index(j.name)]) for j in state.joints if j.actuated)
    return SKCInstant("whole", n, bodies, motors, loop_jacobian=loop)


def soc_skcs(state: LinkageState) -> list[SKCInstant]:
    """SKCs in solving order for a single-loop planar linkage cut at "C" with grounded motors.

    1. The dyad of the two links meeting at C (coupling degree 0): a grounded child-side link turns
       about its pivot carrying the other, which turns about C; otherwise the pair moves freely
       (x, z, a rotation, and the turn at C). Released: the pins joining the dyad to the rest.
    2. Each remaining link alone, from its ground pin (released, with its motor), the dyad's pins known.
    3. The parent-side link of C alone: C released. 4. A grounded child-side link alone: its pivot released.
    In-plane pin forces only (components fx, fz); motor torques are efforts.

    Args:
        state: the linkage's state.

    Returns:
        The SKCs in solving order.
    """
    st = state
    cut = st.joint("C")
    parent_of = {j.child: j for j in st.joints if j.name != "C"}
    jp, jq = parent_of[cut.parent], parent_of[cut.child]

    def site(joint: PlanarJoint, chain: Chain, sign: float) -> WrenchSite:
        return pin_site(joint.name, joint.point, chain, sign)

    def free(link: str) -> Chain:
        return free_chain(parent_of[link].point)

    if jq.parent is None:
        chain_p, chain_q = (jq.point, cut.point), (jq.point, None)
        released = (site(jp, chain_p, 1.0),)
    else:
        chain_p, chain_q = ("x", "z", jp.point, None), ("x", "z", jp.point, cut.point)
        released = (site(jp, chain_p, 1.0), site(jq, chain_q, 1.0))
    dyad = (body_load(st.links[cut.parent], chain_p), body_load(st.links[cut.child], chain_q))
    skcs = [SKCInstant("dyad at C", len(chain_p), dyad, released=released)]
    solved = {r.joint for r in released}
    for j in st.joints:
        if j.name == "C" or j.child in (cut.parent, cut.child):
            continue
        chain = free(j.child)
        known = tuple(site(k, chain, -1.0) for k in st.joints if k.parent == j.child and k.name in solved)
        motors = ((j.name, motor_column(chain)),) if j.actuated else ()
        skcs.append(
            SKCInstant(j.child, 3, (body_load(st.links[j.child], chain),), motors, (site(j, chain, 1.0),), known)
        )
    chain = free(cut.parent)
    skcs.append(
        SKCInstant(
            cut.parent,
            3,
            (body_load(st.links[cut.parent], chain),),
            released=(site(cut, chain, -1.0),),
            known=(site(jp, chain, 1.0),),
        )
    )
    if jq.parent is None:
        chain = free(cut.child)
        skcs.append(
            SKCInstant(
                cut.child,
                3,
                (body_load(st.links[cut.child], chain),),
                released=(site(jq, chain, 1.0),),
                known=(site(cut, chain, 1.0),),
            )
        )
    return skcs
