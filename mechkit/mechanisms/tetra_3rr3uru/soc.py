"""Sequential SOC inverse dynamics of the 3RR-3URU unit along the paper's fold (numpy only).

Independent of Pinocchio's kinematics and dynamics: the motion of every body comes from the
paper's node positions (eq. 6-7), the web-joint map of `truss.joint_state.web_joint_motion` and a
closed-form closure of each URU rod; the tree (joint axes and points) is re-derived here from the
same geometry, not read from the URDF. Only masses, COM offsets and inertias are read from the
model description. Time derivatives: complex step (first), central differences of complex-step
derivatives (second).

SKC decomposition of the unit (declared in `skcs`):
  1. "unit": the spanning tree (18 joint coordinates) with the three middle hinges AB_M, AE_M,
     BE_M released (3 forces + 2 moments normal to the hinge each): 3 efforts + 15 unknowns
     against 18 virtual-work equations (coupling degree 0, square).
  2. one SKC per body, leaves first: the body with its parent joint released (6 unknowns), its
     child joints and cut hinges known: the reaction of every tree joint.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from mechkit.base.exceptions import InvalidParameters
from mechkit.base.spatial import rot_y, skew
from mechkit.mechanisms.tetra_3rr3uru.actuation import ACTUATED
from mechkit.mechanisms.truss.drives import alpha_law, gamma_law
from mechkit.mechanisms.truss.geometry import rot_axis
from mechkit.mechanisms.truss.params import TetraParams
from mechkit.validation.soc import BodyLoad, SKCInstant, SOCResult, WrenchSite, solve_soc

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

ROD_NODES = {"AB": ("A", "B"), "AE": ("A", "E"), "BE": ("B", "E")}
_CS_STEP = 1e-30  # complex step, s
_FD_STEP = 1e-2  # s: central difference of complex-step derivatives (motion time scale ~ 10^3 s)


def _unit(v):
    return v / np.sqrt(v @ v)


def _frame(u, v):
    """Columns (u, v, u x v) of two perpendicular unit vectors."""
    return np.column_stack([u, v, np.cross(u, v)])


@dataclass(frozen=True)
class TreeJoint:
    """A revolute of the unit's spanning tree: name, parent body ('ground'), child body, axis (world,
    reference), and the node at which it sits."""

    name: str
    parent: str
    child: str
    axis: np.ndarray
    node: str


class UnitMotion:
    """The unit's tree and the world motion of each of its bodies along the paper's fold.

    Bodies are named as the URDF links; every body frame is parallel to the world in the
    reference configuration and has its origin at its parent joint (a node).
    """

    def __init__(self, p: TetraParams):
        self.p = p
        self.geometry = p.geometry()
        T = rot_y(p.gamma_ref)
        self.tangent = {k: T @ self.geometry.tangent(k) for k in ("A", "B", "E")}
        self.normal = T @ np.array([0.0, 0.0, 1.0])
        ref = self.ref_nodes = self.nodes(p.alpha_ref, p.gamma_ref)
        self.rods = {}
        for rod, (a, b) in ROD_NODES.items():
            link = p.l1 if a == "A" else p.l2
            c = ref[b] - ref[a]
            w = _unit(self.normal - (self.normal @ c) / (c @ c) * c)
            n = _unit(np.cross(c, w))
            mid = 0.5 * (ref[a] + ref[b]) + np.sqrt(link**2 - c @ c / 4.0) * w
            self.rods[rod] = {"link": link, "n": n, "mid": mid, a: _unit(mid - ref[a]), b: _unit(mid - ref[b])}
        t = self.tangent
        joints = [
            TreeJoint("AH_A", "ground", "rod_AH", t["A"], "A"),
            TreeJoint("AH_H", "rod_AH", "node_H", t["A"], "H"),
            TreeJoint("BH_H", "node_H", "rod_BH", t["B"], "H"),
            TreeJoint("BH_B", "rod_BH", "node_B", t["B"], "B"),
            TreeJoint("EH_H", "node_H", "rod_EH", t["E"], "H"),
            TreeJoint("EH_E", "rod_EH", "node_E", t["E"], "E"),
        ]
        for rod, (a, b) in ROD_NODES.items():
            for node in (a, b):
                parent = "ground" if node == "A" else f"node_{node}"
                joints += [
                    TreeJoint(f"{rod}_{node}1", parent, f"{rod}_{node}_cross", self.rods[rod][node], node),
                    TreeJoint(f"{rod}_{node}2", f"{rod}_{node}_cross", f"{rod}_{node}_link", self.rods[rod]["n"], node),
                ]
        self.joints = joints
        self.parent_joint = {j.child: j for j in joints}
        self.bodies = [j.child for j in joints]  # parents before children
        self.index = {j.name: i for i, j in enumerate(joints)}

    def nodes(self, alpha: complex, gamma: complex) -> dict:
        """Eq. (6)-(7): node positions of the unit, m (complex-safe).

        Args:
            alpha: the fold angle, rad (complex for complex-step derivatives).
            gamma: the tilt, rad.

        Returns:
            Node -> position (3,), m.
        """
        local = self.geometry.unit_local(alpha)
        return {k: rot_y(gamma) @ v for k, v in local.items()}

    def poses(self, t: complex) -> tuple[dict, dict]:
        """(rotation, origin) of every body at time t, world (complex-safe in t).

        Args:
            t: time, s (complex for complex-step derivatives).

        Returns:
            (body -> rotation (3, 3), body -> origin (3,) m).
        """
        p = self.p
        alpha, gamma = alpha_law(t), gamma_law(t)
        da, dg = alpha - p.alpha_ref, gamma - p.gamma_ref
        nodes = self.nodes(alpha, gamma)
        R = {"ground": np.eye(3), "rod_AH": rot_y(dg - da), "node_H": rot_y(dg)}
        for k in ("B", "E"):
            R[f"rod_{k}H"] = R["node_H"] @ rot_axis(self.tangent[k], -da)
            R[f"node_{k}"] = R["node_H"] @ rot_axis(self.tangent[k], -dg)
        R["node_A"] = np.eye(3)
        origin = {
            "rod_AH": nodes["A"],
            "node_H": nodes["H"],
            "rod_BH": nodes["H"],
            "rod_EH": nodes["H"],
            "node_B": nodes["B"],
            "node_E": nodes["E"],
        }
        for rod, (a, b) in ROD_NODES.items():
            g = self.rods[rod]
            ua, ub = R[f"node_{a}"] @ g[a], R[f"node_{b}"] @ g[b]
            n = np.cross(ua, ub)
            n = n * np.sign(float(np.real(n @ g["n"]))) / np.sqrt(n @ n)
            c = nodes[b] - nodes[a]  # n x c points to the folded side, as w did in the reference (n = c x w)
            mid = 0.5 * (nodes[a] + nodes[b]) + np.sqrt(g["link"] ** 2 - c @ c / 4.0) * _unit(np.cross(n, c))
            for node, u in ((a, ua), (b, ub)):
                d_ref, d = _unit(g["mid"] - self.ref_nodes[node]), _unit(mid - nodes[node])
                R[f"{rod}_{node}_cross"] = _frame(u, n) @ _frame(g[node], g["n"]).T
                R[f"{rod}_{node}_link"] = _frame(n, d) @ _frame(g["n"], d_ref).T
                origin[f"{rod}_{node}_cross"] = origin[f"{rod}_{node}_link"] = nodes[node]
            origin[f"{rod}_M"] = mid
        return R, origin


@dataclass(frozen=True)
class BodyState:
    """World motion of one body: rotation, origin (joint point), COM, angular velocity and
    acceleration, COM acceleration (SI)."""

    R: np.ndarray
    origin: np.ndarray
    com: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray
    com_acceleration: np.ndarray


def _vee(S: np.ndarray) -> np.ndarray:
    return 0.5 * np.array([S[2, 1] - S[1, 2], S[0, 2] - S[2, 0], S[1, 0] - S[0, 1]])


def body_states(motion: UnitMotion, levers: dict[str, np.ndarray], t: float) -> tuple[dict, dict]:
    """Every body's `BodyState` at time t, and the world points of the middle hinges (m).

    Args:
        motion: the unit's analytic motion.
        levers: COM offset of each body in its frame (m), from the model description.
        t: time, s.

    Returns:
        (body -> `BodyState`, rod -> world point (3,) of its middle hinge).
    """

    def rates(tt: float) -> tuple[dict, dict, dict]:
        R, o = motion.poses(tt + 1j * _CS_STEP)
        Rr = {k: np.real(v) for k, v in R.items()}
        omega = {k: _vee((np.imag(R[k]) / _CS_STEP) @ Rr[k].T) for k in levers}
        com_vel = {k: np.imag(o[k] + R[k] @ levers[k]) / _CS_STEP for k in levers}
        return Rr, {k: np.real(v) for k, v in o.items()}, (omega, com_vel)

    R, o, (omega, _) = rates(t)
    _, _, (w_plus, v_plus) = rates(t + _FD_STEP)
    _, _, (w_minus, v_minus) = rates(t - _FD_STEP)
    states = {
        k: BodyState(
            R[k],
            o[k],
            o[k] + R[k] @ levers[k],
            omega[k],
            (w_plus[k] - w_minus[k]) / (2 * _FD_STEP),
            (v_plus[k] - v_minus[k]) / (2 * _FD_STEP),
        )
        for k in levers
    }
    return states, {rod: o[f"{rod}_M"] for rod in ROD_NODES}


def _point_jacobian(motion: UnitMotion, states: dict, body: str, point: np.ndarray) -> np.ndarray:
    """(6, 18): virtual displacement of `point` fixed to `body` and the body's virtual rotation."""
    J = np.zeros((6, len(motion.joints)))
    while body != "ground":
        joint = motion.parent_joint[body]
        parent_R = np.eye(3) if joint.parent == "ground" else states[joint.parent].R
        axis = parent_R @ joint.axis
        k = motion.index[joint.name]
        J[:3, k] = np.cross(axis, point - states[joint.child].origin)
        J[3:, k] = axis
        body = joint.parent
    return J


def _site(point: np.ndarray, com: np.ndarray) -> np.ndarray:
    """(6, 6) site Jacobian of a point of a free body over (COM translation, rotation)."""
    J = np.zeros((6, 6))
    J[:3, :3], J[:3, 3:], J[3:, 3:] = np.eye(3), -skew(point - com), np.eye(3)
    return J


def skcs(motion: UnitMotion, inertias: dict[str, tuple[float, np.ndarray, np.ndarray]], t: float) -> list[SKCInstant]:
    """The unit's SKC decomposition at time t (see the module docstring).

    Args:
        motion: the unit's analytic motion.
        inertias: body -> (mass kg, COM offset in the body frame m, inertia about the COM in the
            body frame kg m^2), the body frame being world-parallel in the reference.
        t: time, s.

    Returns:
        The SKCs in solve order.
    """
    states, hinges = body_states(motion, {k: v[1] for k, v in inertias.items()}, t)
    n = len(motion.joints)
    loads = []
    for body in motion.bodies:
        mass, _, inertia = inertias[body]
        s = states[body]
        J = _point_jacobian(motion, states, body, s.com)
        loads.append(BodyLoad(body, mass, s.R @ inertia @ s.R.T, s.com_acceleration, s.omega, s.alpha, J[:3], J[3:]))
    actuators = [(joint, np.eye(n)[motion.index[joint]]) for joint in ACTUATED]
    cuts = []
    for rod, (a, b) in ROD_NODES.items():
        side_a, side_b = f"{rod}_{a}_link", f"{rod}_{b}_link"
        jac = _point_jacobian(motion, states, side_b, hinges[rod]) - _point_jacobian(
            motion, states, side_a, hinges[rod]
        )
        axis = states[side_a].R @ motion.rods[rod]["n"]
        t1 = _unit(np.cross(axis, [1.0, 0, 0] if abs(axis[0]) < 0.9 else [0, 1.0, 0]))
        basis = np.zeros((6, 5))
        basis[:3, :3], basis[3:, 3], basis[3:, 4] = np.eye(3), t1, np.cross(axis, t1)
        cuts.append(WrenchSite(f"{rod}_M", jac, 1.0, basis=basis))
    out = [SKCInstant("unit", n, loads, actuators, released=cuts)]
    for body in reversed(motion.bodies):
        mass, _, inertia = inertias[body]
        s = states[body]
        jv, jw = np.hstack([np.eye(3), np.zeros((3, 3))]), np.hstack([np.zeros((3, 3)), np.eye(3)])
        load = BodyLoad(body, mass, s.R @ inertia @ s.R.T, s.com_acceleration, s.omega, s.alpha, jv, jw)
        joint = motion.parent_joint[body]
        released = [WrenchSite(joint.name, _site(s.origin, s.com), 1.0)]
        known = [
            WrenchSite(j.name, _site(states[j.child].origin, s.com), -1.0) for j in motion.joints if j.parent == body
        ]
        for rod, (a, b) in ROD_NODES.items():
            for node, sign in ((a, -1.0), (b, 1.0)):
                if body == f"{rod}_{node}_link":
                    known.append(WrenchSite(f"{rod}_M", _site(hinges[rod], s.com), sign))
        out.append(SKCInstant(body, 6, [load], released=released, known=known))
    return out


def model_inertias(mech: Mechanism) -> dict[str, tuple[float, np.ndarray, np.ndarray]]:
    """Mass, COM offset and inertia of each body of the unit, read from the model description.

    Args:
        mech: the unit.

    Returns:
        Body -> (mass kg, COM offset (3,) in the body frame m, inertia (3, 3) about the COM kg m^2).

    Raises:
        InvalidParameters: the mechanism is not the 3RR-3URU unit.
    """
    motion_bodies = {j.name: j.child for j in UnitMotion(mech.params).joints}
    out = {}
    for j in range(1, mech.model.njoints):
        name = mech.model.names[j]
        if name not in motion_bodies:
            raise InvalidParameters("mech", mech.spec.name, f"joint {name!r} is not a joint of the 3RR-3URU unit")
        inertia = mech.model.inertias[j]
        out[motion_bodies[name]] = (float(inertia.mass), inertia.lever.copy(), inertia.inertia.copy())
    return out


def solve(mech: Mechanism, t: float) -> SOCResult:
    """SOC inverse dynamics of the unit at time t of the paper's fold (gravity from the model).

    Args:
        mech: the unit.
        t: time along the fold, s.

    Returns:
        Efforts (N m) and every joint's reaction (world wrench (6,)).
    """
    motion = UnitMotion(mech.params)
    return solve_soc(skcs(motion, model_inertias(mech), t), np.array(mech.model.gravity.linear))
