"""The composite's fold, as data, against the paper's eq. (6)-(13) (`SPEC.studies`; figures in
`figures`, numbers in docs/mechanisms/deployable_9rr12uru.md).

`fold_study` solves the 200 s fold (closure at every `step` s, warm start) and reads, at each
sample, node F's and node I's centres and node B's RPY angles from the model and from the paper's
equations (our reading; the printed eq. (9) too), the closure residual and the drive torques of the
constrained RNEA.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechkit.base.spatial import rot_y
from mechkit.mechanism import Mechanism
from mechkit.mechanisms.truss.drives import DriveState, drive_state
from mechkit.mechanisms.truss.fold import fold, fold_times
from mechkit.mechanisms.truss.geometry import R_B0_ANGLES, euler_xyz, rot_axis, rpy_angles
from mechkit.mechanisms.truss.nodes import node_positions, node_velocity

#: The paper's gamma_x of node B at t = 200 s (deg, section 3.2; theory, Adams 84.9368).
PAPER_END_GAMMA_X = 85.5133


@dataclass(frozen=True)
class FoldRow:
    """One sample of the fold, model against equations (SI, world frame of node A).

    Attributes:
        node_f_eq, node_f_model: (3,) node F's centre by eq. (7)-(8) and by the model, m.
        position_error: largest |model - equation| over every node's centre, m.
        node_i_speed_eq, node_i_speed_model: node I's speed, d/dt of eq. (8) and from the closure velocities, m/s.
        rpy_eq, rpy_model, rpy_printed: (3,) node B's RPY angles by eq. (9)-(13) (our reading), by the
            model and by eq. (9) as printed, rad.
        residual: largest closure residual.
        efforts: drive joint -> torque (N m), constrained RNEA.
    """

    node_f_eq: np.ndarray
    node_f_model: np.ndarray
    position_error: float
    node_i_speed_eq: float
    node_i_speed_model: float
    rpy_eq: np.ndarray
    rpy_model: np.ndarray
    rpy_printed: np.ndarray
    residual: float
    efforts: dict[str, float]


@dataclass(frozen=True)
class Fold:
    """The fold sample by sample: times (s), the drive states, one `FoldRow` each, and the drive joints."""

    t: np.ndarray
    drives: list[DriveState]
    rows: list[FoldRow]
    actuated: tuple[str, ...]


def fold_study(mech: Mechanism, step: float = 1.0) -> Fold:
    """The 200 s fold sampled every `step` s, model against the paper's equations.

    Args:
        mech: the composite.
        step: the sampling step, s.

    Returns:
        The fold: times, states, and per sample the model's and the paper's values.
    """
    p, g = mech.params, mech.params.geometry()
    samples = fold(mech, fold_times(step))
    t = np.array([s.t for s in samples])
    states = [drive_state(x) for x in t]
    node_b = mech.model.getFrameId("node_B")
    b_initial = rot_y(p.gamma_ref) @ euler_xyz(R_B0_ANGLES)  # the paper's node-B frame at t = 0, A axes
    rows = []
    for sample, s in zip(samples, states):
        eq = g.node_positions(s.alpha, s.gamma)
        model = node_positions(mech, sample.q)
        printed = rpy_angles(rot_y(s.gamma) @ rot_axis(g.tangent("B"), s.gamma - p.gamma_ref) @ euler_xyz(R_B0_ANGLES))
        rows.append(
            FoldRow(
                eq["F"],
                model["F"],
                max(np.abs(model[k] - eq[k]).max() for k in model),
                float(np.linalg.norm(g.node_velocities(s.alpha, s.gamma, s.alpha_rate, s.gamma_rate)["I"])),
                float(np.linalg.norm(node_velocity(mech, sample.q, sample.v, "I"))),
                g.node_rpy("B", s.gamma, p.gamma_ref),
                rpy_angles(mech.data.oMf[node_b].rotation @ b_initial),
                printed,
                float(np.abs(mech.closure_residual(sample.q)).max()),
                dict(mech.inverse_dynamics(sample.q, sample.v, sample.a, determinacy=False).efforts),
            )
        )
    return Fold(t, states, rows, tuple(mech.actuated))


def worst_deviations(f: Fold) -> dict[str, float]:
    """The largest deviation of the model from the equations, per quantity, and node B's gamma_x at the end (deg).

    Args:
        f: the fold study.

    Returns:
        Quantity -> largest deviation (m, m/s or rad, as the quantity), and "node_B_gamma_x_end_deg".
    """
    return {
        "node_position": max(r.position_error for r in f.rows),
        "closure_residual": max(r.residual for r in f.rows),
        "node_I_speed": max(abs(r.node_i_speed_eq - r.node_i_speed_model) for r in f.rows),
        "node_B_rpy": max(np.abs(np.angle(np.exp(1j * (r.rpy_eq - r.rpy_model)))).max() for r in f.rows),
        "gamma_x_end_deg": float(np.degrees(f.rows[-1].rpy_eq[0])),
        "gamma_x_end_printed_deg": float(np.degrees(f.rows[-1].rpy_printed[0])),
    }


def fold_lines(f: Fold) -> list[str]:
    """`worst_deviations` as text lines.

    Args:
        f: the fold study.

    Returns:
        Text lines.
    """
    return [f"{key:26s} {value:.3e}" for key, value in worst_deviations(f).items()]
