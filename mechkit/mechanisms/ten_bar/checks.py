"""Ten-bar cross-checks: each quantity by independent routes, and the `mechkit report` rows.

- kinematics: closed-form pose (numpy) vs the full closure solve vs the patent's dimension
  reduction on reduced Pinocchio models;
- dynamics at one state: Pinocchio's constrained ABA vs the patent's Lagrange first-kind solve;
- reactions at one state: Pinocchio's constrained RNEA (`Mechanism.inverse_dynamics`) vs the
  Lagrange multipliers vs the SOC virtual work, for the motor torques and the in-plane forces of
  all 12 revolute pairs (the determinate components of a planar pin).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from mechkit.mechanisms.ten_bar import dynamics as td
from mechkit.mechanisms.ten_bar import geometry as geo
from mechkit.mechanisms.ten_bar import kinematics as tk
from mechkit.mechanisms.ten_bar import soc as ts
from mechkit.mechanisms.ten_bar.lagrange_deployment import LagrangeJointDeployment
from mechkit.mechanisms.ten_bar.lagrange_model import lagrange_linkage
from mechkit.mechanisms.ten_bar.params import MOTORS, TenBarParams, motor_law

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism


@dataclass(frozen=True)
class Reactions:
    """One method's answer at one instant.

    Attributes:
        efforts: motor torques (N m, +x towards +z).
        forces: pin forces (N, (fx, fz)), parent on child, world.
    """

    efforts: dict[str, float]
    forces: dict[str, np.ndarray]

    def vector(self) -> np.ndarray:
        """Motor torques (N m, `MOTORS`) then every pair's force components (N, `geometry.PAIRS`), flat."""
        return np.concatenate([[self.efforts[m] for m in MOTORS], *[self.forces[j] for j in geo.PAIRS]])


def reactions_three_ways(mechanism: Mechanism, t: float, q: np.ndarray, v: np.ndarray) -> dict[str, Reactions]:
    """Motor torques and pin forces at a state (q, v) on the manifold at time t, by three methods.

    Pinocchio: accelerations from constrained ABA with the motor laws, then constrained RNEA (the R5
    spring is the mechanism's joint spring in both). Lagrange: A f = P from the same state mapped to
    reference-point coordinates. SOC: virtual work over the SKCs with the Lagrange motion.

    Args:
        mechanism: the ten-bar.
        t: time, s.
        q: configuration (nq,), on the manifold.
        v: velocity (nv,).

    Returns:
        Method ("pinocchio", "lagrange", "soc") -> motor torques (N m) and the 12 pairs' in-plane forces (N).
    """
    deployment = td.PinocchioDeployment(mechanism)
    a, _, _ = deployment.rhs(t, q, v)
    inv = mechanism.inverse_dynamics(q, v, a)
    out = {"pinocchio": Reactions(dict(inv.efforts), {j: inv.reactions[j].wrench[[0, 2]] for j in geo.PAIRS})}
    p = mechanism.params
    qL, vL = td.lagrange_state(p, q, v, mechanism)
    L = lagrange_linkage(p)
    sol = L.solve(qL, vL, motor_law(p, t)[2])
    out["lagrange"] = Reactions(sol.efforts, sol.forces)
    efforts, forces, _ = ts.solve(L, qL, vL, sol.qdd)
    out["soc"] = Reactions(efforts, forces)
    return out


def reactions_along(
    mechanism: Mechanism, trajectory: td.Trajectory, every: int
) -> tuple[np.ndarray, dict[str, list[Reactions]]]:
    """`reactions_three_ways` at every `every`-th sample of a Pinocchio-route trajectory.

    Args:
        mechanism: the ten-bar.
        trajectory: a Pinocchio-route trajectory.
        every: the sampling stride.

    Returns:
        (sample times (s), method -> list of `Reactions`).
    """
    idx = np.arange(0, len(trajectory.t), every)
    out: dict[str, list[Reactions]] = {}
    for k in idx:
        for method, r in reactions_three_ways(mechanism, trajectory.t[k], trajectory.q[k], trajectory.v[k]).items():
            out.setdefault(method, []).append(r)
    return trajectory.t[idx], out


def reaction_disagreement(results: dict[str, Reactions]) -> float:
    """Largest difference between any two methods, relative to the largest value (all 26 numbers).

    Args:
        results: method -> reactions (`reactions_three_ways`).

    Returns:
        The relative difference (-).
    """
    vectors = [r.vector() for r in results.values()]
    scale = max(np.max(np.abs(x)) for x in vectors)
    return float(max(np.max(np.abs(x - y)) for x in vectors for y in vectors) / scale)


def kinematics_disagreement(mechanism: Mechanism, inputs_list: list[dict[str, float]]) -> dict[str, float]:
    """Largest joint-angle difference (rad) between the routes over a sequence of inputs (R1, R3, R5).

    Each solve starts from the previous instant's answer, so consecutive inputs must be close (a
    tracked path), or a route may land on another assembly branch.

    Args:
        mechanism: the ten-bar.
        inputs_list: inputs R1, R3, R5 (rad) along a path.

    Returns:
        {"full_vs_reduction", "full_vs_closed_form"} -> worst difference (rad).
    """
    reduction = tk.DimensionReduction(mechanism)
    names = td.JOINT_ORDER
    q = mechanism.home_q.copy()
    guess = {j: q[mechanism.q_index(j)] for j in names}
    worst = {"full_vs_reduction": 0.0, "full_vs_closed_form": 0.0}
    for inputs in inputs_list:
        q = tk.full_solve(mechanism, inputs, q)
        seq = reduction.solve(inputs, guess)
        closed = geo.pose(mechanism.params, inputs["R1"], inputs["R3"], inputs["R5"]).joint_angles()
        full = {j: q[mechanism.q_index(j)] for j in names}
        worst["full_vs_reduction"] = max(worst["full_vs_reduction"], max(abs(full[j] - seq[j]) for j in names))
        worst["full_vs_closed_form"] = max(
            worst["full_vs_closed_form"],
            max(abs(np.angle(np.exp(1j * (full[j] - closed[j])))) for j in names),
        )
        guess = seq
    return worst


def nominal_inputs(p: TenBarParams, n: int) -> list[dict[str, float]]:
    """Inputs along the motor laws with the rocker moved linearly from stowed to 0 (a kinematic path).

    Args:
        p: the ten-bar's parameters.
        n: how many instants.

    Returns:
        n input sets R1, R3, R5 (rad).
    """
    out = []
    for t in np.linspace(0.0, p.deploy_time, n):
        pos, _, _ = motor_law(p, t)
        out.append({"R1": pos[0], "R3": pos[1], "R5": p.stowed_rocker * (1 - t / p.deploy_time)})
    return out


def self_checks(mechanism: Mechanism) -> dict[str, float]:
    """Rows of `mechkit report ten_bar` (worst error of each check; smaller is better).

    Args:
        mechanism: the ten-bar.

    Returns:
        Check name -> worst error.
    """
    p = mechanism.params
    kin = kinematics_disagreement(mechanism, nominal_inputs(p, 21))
    pin_run = td.PinocchioDeployment(mechanism)
    lag_run = LagrangeJointDeployment(p)
    q0 = mechanism.home_q
    qj = pin_run.joint_angles(q0)
    stretch = {"t_end": 0.05, "dt": 0.01}
    a = td.integrate(pin_run, q0, np.zeros_like(q0), **stretch)
    b = td.integrate(lag_run, qj, np.zeros_like(qj), **stretch)
    t_mid = 0.5 * p.deploy_time
    q_mid = tk.full_solve(mechanism, nominal_inputs(p, 3)[1], q0)
    v_mid = mechanism.velocities(q_mid, {"R1": 0.05, "R3": -0.1, "R5": 0.2}, inputs=("R1", "R3", "R5"))
    return {
        "ten_bar stowed closure residual (m)": float(np.max(np.abs(mechanism.closure_residual(q0)))),
        "ten_bar full closure vs closed form (rad)": kin["full_vs_closed_form"],
        "ten_bar full closure vs dimension reduction (rad)": kin["full_vs_reduction"],
        "ten_bar reactions Pinocchio/Lagrange/SOC (rel)": reaction_disagreement(
            reactions_three_ways(mechanism, t_mid, q_mid, v_mid)
        ),
        "ten_bar deployment 0.05 s Pinocchio vs Lagrange (rad)": float(np.max(np.abs(a.angles - b.angles))),
        "ten_bar deployment closure drift (m)": float(max(a.residual.max(), b.residual.max())),
    }
