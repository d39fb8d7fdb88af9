"""The ten-bar's SKC decomposition for the sequential SOC virtual-work method (numpy only).

Each SKC's virtual coordinates are the reference-point coordinates (x, z, phi) of its links; its
internal pins are its loop Jacobian; the motion (positions, rates, accelerations of every link)
comes from the patent's Lagrange first-kind solution, never from Pinocchio. Order, from the tip of
the linkage to the wall (equations x unknowns):

    dyad     l48 l87    releases R4, R7c (R8 internal)                              4 x 4
    l87      l87        knows R7c, releases R8                                      3 x 2
    panel2   l34        knows R4, releases R3 (fx, fz and my: the motor torque)     3 x 3
    four_bar l79 l910   releases R7b, R10 (R9 internal)                             4 x 4
    l910     l910       knows R10, releases R9                                      3 x 2
    rocker   l56 l67    releases R5, R7a (R6 internal); the R5 spring is a load     4 x 4
    l67      l67        knows R7a, releases R6                                      3 x 2
    hub      l27        knows R7a R7b R7c, releases R2                              3 x 2
    panel1   l123       knows R2 R3 R10, releases R1, solves the R1 motor           3 x 3

Every one of the 12 pairs is released once. The single-link SKCs inside a solved chain (l87, l910,
l67) have one equation more than unknowns, and so does the hub l27, whose extra equation is the
passive DOF's equation of motion (which the patent's kinematic split cannot supply): their
`consistency` residuals check the motion and the reactions already found.
"""

from __future__ import annotations

import numpy as np

from mechkit.mechanisms.ten_bar import geometry as geo
from mechkit.validation import lagrange
from mechkit.validation.soc import BodyLoad, SKCInstant, SOCResult, WrenchSite, solve_soc

FORCE = (0, 2)  # in-plane force components of a pin of the x-z plane
FORCE_AND_AXIS_MOMENT = (0, 2, 4)

SKCS = (
    ("dyad", ("l48", "l87"), {"R4": FORCE, "R7c": FORCE}, (), ()),
    ("l87", ("l87",), {"R8": FORCE}, ("R7c",), ()),
    ("panel2", ("l34",), {"R3": FORCE_AND_AXIS_MOMENT}, ("R4",), ()),
    ("four_bar", ("l79", "l910"), {"R7b": FORCE, "R10": FORCE}, (), ()),
    ("l910", ("l910",), {"R9": FORCE}, ("R10",), ()),
    ("rocker", ("l56", "l67"), {"R5": FORCE, "R7a": FORCE}, (), ()),
    ("l67", ("l67",), {"R6": FORCE}, ("R7a",), ()),
    ("hub", ("l27",), {"R2": FORCE}, ("R7a", "R7b", "R7c"), ()),
    ("panel1", ("l123",), {"R1": FORCE}, ("R2", "R3", "R10"), ("R1",)),
)
"""(name, links, released joint -> unknown components, known joints, motors solved here)."""

_Y = np.array([0.0, -1.0, 0.0])  # a planar rotation (+x towards +z) is a rotation about -y


def _to3(v2: np.ndarray) -> np.ndarray:
    return np.array([v2[0], 0.0, v2[1]])


def _site(L: lagrange.Linkage, q: np.ndarray, slot: dict[int, int], pin_name: str, components=FORCE) -> WrenchSite:
    """A pin seen from the SKC whose links are `slot` (link index -> position in the SKC)."""
    pin = L.pins[L.pin_index[pin_name]]
    here, point, sign = (pin.b, pin.point_b, 1.0) if pin.b in slot else (pin.a, pin.point_a, -1.0)
    k = slot[here]
    arm = geo.rot(q[3 * here + 2]) @ (point - L.bodies[here].com)
    jac = np.zeros((6, 3 * len(slot)))
    jac[0, 3 * k], jac[2, 3 * k + 1] = 1.0, 1.0
    jac[[0, 2], 3 * k + 2] = [-arm[1], arm[0]]
    jac[3:, 3 * k + 2] = _Y
    return WrenchSite(pin_name, jac, sign, components)


def skc_instants(L: lagrange.Linkage, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray) -> list[SKCInstant]:
    """The nine SKCs at one instant of a Lagrange solution (q, qd, qdd in reference-point coordinates).

    Args:
        L: the Lagrange linkage.
        q: reference-point coordinates (3 per link).
        qd: their rates.
        qdd: their accelerations.

    Returns:
        The SKCs in solve order.
    """
    index = {b.name: i for i, b in enumerate(L.bodies)}
    Cq = L.jacobian(q)
    spring = L.springs[0]
    torque = spring.stiffness * (
        spring.free_angle - L.relative_angle(q, spring.pin)
    ) - spring.damping * L.relative_angle(qd, spring.pin)
    out = []
    for name, links, released, known, motors in SKCS:
        bodies = [index[b] for b in links]
        cols = np.concatenate([[3 * i, 3 * i + 1, 3 * i + 2] for i in bodies])
        n = cols.size
        slot = {i: k for k, i in enumerate(bodies)}
        loads = []
        for i in bodies:
            b, k = L.bodies[i], slot[i]
            jv, jw = np.zeros((3, n)), np.zeros((3, n))
            jv[0, 3 * k], jv[2, 3 * k + 1], jw[:, 3 * k + 2] = 1.0, 1.0, _Y
            loads.append(
                BodyLoad(
                    b.name,
                    b.mass,
                    b.inertia * np.eye(3),
                    _to3(qdd[3 * i : 3 * i + 2]),
                    _Y * qd[3 * i + 2],
                    _Y * qdd[3 * i + 2],
                    jv,
                    jw,
                )
            )

        internal = [k for k, p in enumerate(L.pins) if p.b in slot and p.a in slot]
        loop = Cq[np.concatenate([[2 * k, 2 * k + 1] for k in internal])][:, cols] if internal else None
        external = []
        if index["l56"] in slot:
            moment = np.concatenate([np.zeros(3), _Y * torque])
            external.append((moment, _site(L, q, slot, spring.pin).jacobian))
        actuators = []
        for motor in motors:
            direction = np.zeros(n)
            direction[3 * slot[L.pins[L.pin_index[motor]].b] + 2] = 1.0
            actuators.append((motor, direction))
        out.append(
            SKCInstant(
                name,
                n,
                loads,
                actuators,
                [_site(L, q, slot, j, c) for j, c in released.items()],
                [_site(L, q, slot, j) for j in known],
                external,
                loop,
            )
        )
    return out


def solve(
    L: lagrange.Linkage, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray
) -> tuple[dict[str, float], dict[str, np.ndarray], SOCResult]:
    """SOC efforts (N m, +x towards +z) and the 12 pairs' in-plane forces (N, (fx, fz), parent on child).

    The R3 motor torque is the axis moment of the R3 reaction: u3 = -my.

    Args:
        L: the Lagrange linkage.
        q: reference-point coordinates (3 per link).
        qd: their rates.
        qdd: their accelerations.

    Returns:
        (motor -> torque, pair -> (fx, fz), the SOC result).
    """
    result = solve_soc(skc_instants(L, q, qd, qdd), gravity=np.array([L.gravity[0], 0.0, L.gravity[1]]))
    efforts = {"R1": result.efforts["R1"], "R3": -float(result.reactions["R3"][4])}
    forces = {j: result.reactions[j][[0, 2]] for j in geo.PAIRS}
    return efforts, forces, result


__all__ = ["SKCS", "skc_instants", "solve"]
