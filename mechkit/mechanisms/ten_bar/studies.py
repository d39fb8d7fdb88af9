"""The ten-bar's studies, as data: the deployment with every cross-check, and the deployment's figures
(`SPEC.studies`; figures in `figures`, numbers in docs/mechanisms/ten_bar.md).

- `cross_checks`: the deployment, stowed to deployed, by Pinocchio's constrained ABA and by the
  patent's Lagrange first-kind method from the same parameters (fixed steps of the simulator with
  projection); the Lagrange method in its own coordinates converging at fourth order; reactions by
  constrained RNEA, Lagrange multipliers and SOC at sampled instants; the full closure solve against
  the dimension reduction and the closed form along the motion; where the methods fail (kinematic
  split, unstabilised drift, distance from singular poses).
- `deployment`: one Pinocchio-route deployment with the spring torque, the wall supports by
  constrained RNEA and the Lagrange multipliers, and the drift of each stabilisation.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from mechkit.mechanism import Mechanism
from mechkit.mechanisms.ten_bar import checks as tc
from mechkit.mechanisms.ten_bar import dynamics as td
from mechkit.mechanisms.ten_bar import geometry as geo
from mechkit.mechanisms.ten_bar import lagrange_model as lm
from mechkit.mechanisms.ten_bar import limits as tl
from mechkit.mechanisms.ten_bar import params as tp
from mechkit.mechanisms.ten_bar.lagrange_deployment import LagrangeDeployment, LagrangeJointDeployment
from mechkit.mechanisms.ten_bar.params import TenBarParams

#: The drift study: its duration and fixed step (s).
DRIFT_END, DRIFT_STEP = 5.0, 0.02
#: fixed steps (s) of the own-coordinates convergence study, over its first `CONVERGENCE_END` s.
CONVERGENCE_STEPS, CONVERGENCE_END = (0.02, 0.01, 0.005), 0.4


def drift_runs(mech: Mechanism) -> dict[str, td.Trajectory]:
    """The first `DRIFT_END` s at `DRIFT_STEP` under each stabilisation of `limits.STABILISATIONS`, by label.

    Args:
        mech: the ten-bar.

    Returns:
        Label -> trajectory.
    """
    return {
        label: tl.drift(mech, DRIFT_END, DRIFT_STEP, baumgarte, project)
        for label, baumgarte, project in tl.STABILISATIONS
    }


@dataclass(frozen=True)
class CrossChecks:
    """The deployment and its cross-checks.

    Attributes:
        params: the design.
        pinocchio, lagrange: the deployment by each route (joint coordinates, same step).
        dt: the fixed step (s).
        seconds: wall time of each route (s), by route.
        convergence: (dt s, max angle difference rad) of the own-coordinates Lagrange run against
            Pinocchio over the first `CONVERGENCE_END` s.
        reaction_times: (k,) instants (s) of the three-way reactions.
        reaction_disagreement: worst relative difference of the three methods over them.
        reaction_peak: largest value they hold (N or N m).
        kinematics: route pair -> worst joint-angle difference (rad) along the deployment.
        kinematic_instants: how many instants the kinematics were compared at.
        split: what the motors alone leave free at the stowed pose.
        free_direction: that free motion's rate of each tree joint (rad/s per unit).
        drift: stabilisation -> largest closure residual (m) over the drift study.
        margins: loop -> (m,) sine of the angle at its closing hinge along the deployment.
    """

    params: TenBarParams
    pinocchio: td.Trajectory
    lagrange: td.Trajectory
    dt: float
    seconds: dict[str, float]
    convergence: list[tuple[float, float]]
    reaction_times: np.ndarray
    reaction_disagreement: float
    reaction_peak: float
    kinematics: dict[str, float]
    kinematic_instants: int
    split: tl.KinematicSplit
    free_direction: dict[str, float]
    drift: dict[str, float]
    margins: dict[str, np.ndarray]


def cross_checks(mech: Mechanism, dt: float = 0.005, t_end: float | None = None, samples: int = 9) -> CrossChecks:
    """The deployment by both routes and every cross-check.

    Args:
        mech: the ten-bar.
        dt: fixed step (s).
        t_end: stop early (s); default: the whole deployment.
        samples: instants of the three-way reactions.

    Returns:
        Both trajectories, their agreement, the convergence order, the three-way reactions and the timings.
    """
    p = mech.params
    pin_run = td.PinocchioDeployment(mech)
    clock = time.perf_counter()
    a = td.deploy(pin_run, mech.home_q, dt, t_end)
    seconds = {"Pinocchio": time.perf_counter() - clock}
    clock = time.perf_counter()
    b = td.deploy(LagrangeJointDeployment(p), pin_run.joint_angles(mech.home_q), dt, t_end)
    seconds["Lagrange"] = time.perf_counter() - clock
    own = LagrangeDeployment(p)
    q_own = lm.lagrange_coordinates(p, geo.stowed_pose(p))
    convergence = [
        (
            step,
            float(
                np.max(
                    np.abs(
                        td.deploy(pin_run, mech.home_q, step, CONVERGENCE_END).angles
                        - td.deploy(own, q_own, step, CONVERGENCE_END).angles
                    )
                )
            ),
        )
        for step in CONVERGENCE_STEPS
    ]
    every = max(1, (len(a.t) - 1) // (samples - 1))
    times, results = tc.reactions_along(mech, a, every)
    worst = max(tc.reaction_disagreement({k: v[i] for k, v in results.items()}) for i in range(len(times)))
    peak = max(np.max(np.abs(r.vector())) for r in results["pinocchio"])
    motors = [td.JOINT_ORDER.index(j) for j in tp.MOTORS]
    r5 = td.JOINT_ORDER.index(tp.PASSIVE)
    inputs = [{"R1": x[motors[0]], "R3": x[motors[1]], "R5": x[r5]} for x in a.angles[::20]]
    split = tl.kinematic_split(mech, mech.home_q)
    return CrossChecks(
        p,
        a,
        b,
        dt,
        seconds,
        convergence,
        times,
        worst,
        float(peak),
        tc.kinematics_disagreement(mech, inputs),
        len(inputs),
        split,
        {j: float(split.direction[mech.v_index(j)]) for j in td.JOINT_ORDER},
        {label: float(run.residual.max()) for label, run in drift_runs(mech).items()},
        tl.loop_margins(p, a.angles[::10]),
    )


def cross_check_lines(c: CrossChecks) -> list[str]:
    """The cross-checks as text, one finding a line.

    Args:
        c: the cross-checks.

    Returns:
        Text lines.
    """
    a, b, p = c.pinocchio, c.lagrange, c.params
    motors = [td.JOINT_ORDER.index(j) for j in tp.MOTORS]
    rocker = np.degrees(a.angles[:, td.JOINT_ORDER.index(tp.PASSIVE)])
    torques = ", ".join(
        f"{j} [{a.torques[:, k].min():.3f}, {a.torques[:, k].max():.3f}]" for k, j in enumerate(tp.MOTORS)
    )
    out = [
        f"Deployment 0..{a.t[-1]:g} s (motor laws end at {p.deploy_time:g} s)",
        f"  fixed step dt = {c.dt * 1e3:g} ms, projection after each step",
        f"  final motor angles (deg): {np.degrees(a.angles[-1, motors]).round(9)} (deployed: 0, 0)",
        (
            f"  rocker R5 (deg): stowed {rocker[0]:.2f}, range [{rocker.min():.2f}, {rocker.max():.2f}], "
            f"final {rocker[-1]:.2f}"
        ),
        f"  motor torques (N m): {torques}",
        f"  closure residual max (m): Pinocchio {a.residual.max():.2e}, Lagrange {b.residual.max():.2e}",
        f"  energy balance |E - W - E0| max (J): Pinocchio {a.energy_error:.2e}, Lagrange {b.energy_error:.2e}",
        (
            f"  energy E = kinetic + gravity + spring spans {np.ptp(a.energy):.2f} J; "
            f"work of motors minus damper {a.work[-1]:.2f} J"
        ),
        (
            "  Pinocchio vs Lagrange (same step, joint coordinates): "
            f"angles {np.max(np.abs(a.angles - b.angles)):.2e} rad, "
            f"torques {np.max(np.abs(a.torques - b.torques)):.2e} N m"
        ),
        (
            f"  wall time: Pinocchio {c.seconds['Pinocchio']:.1f} s, Lagrange {c.seconds['Lagrange']:.1f} s "
            f"({len(a.t) - 1} steps)"
        ),
        (
            f"Lagrange in its own coordinates (x, z, phi per link) vs Pinocchio, first {CONVERGENCE_END:g} s "
            "(spring release):"
        ),
    ]
    previous = None
    for dt, diff in c.convergence:
        order = "" if previous is None else f", order {math.log2(previous / diff):.2f}"
        out.append(f"  dt = {dt * 1e3:5.1f} ms: max angle difference {diff:.2e} rad{order}")
        previous = diff
    out += [
        f"Reactions at {len(c.reaction_times)} instants (2 motor torques + in-plane forces of the 12 pairs,",
        "  R1 and R5 the wall supports):",
        f"  Pinocchio RNEA vs Lagrange multipliers vs SOC, worst relative difference {c.reaction_disagreement:.2e}",
        f"  largest value {c.reaction_peak:.2f} (N or N m)",
        (
            f"Kinematics along the deployment ({c.kinematic_instants} instants): full closure vs dimension reduction "
            f"{c.kinematics['full_vs_reduction']:.2e} rad, vs closed form {c.kinematics['full_vs_closed_form']:.2e} rad"
        ),
        "Where the methods fail:",
        (
            f"  motors alone: {c.split.nullity} joint motion left free (five-bar unit with R1 only: "
            f"{c.split.five_bar_nullity}); free direction (rad/s per unit): "
            + ", ".join(f"{j} {rate:+.3f}" for j, rate in c.free_direction.items())
        ),
    ]
    out += [
        f"  0..{DRIFT_END:g} s at dt = {DRIFT_STEP * 1e3:g} ms, {label:28s}: closure residual max {residual:.2e} m"
        for label, residual in c.drift.items()
    ]
    out.append(
        "  distance from singular poses over the deployment (min sine of the angle at the closing hinge): "
        + ", ".join(f"{k} {v.min():.3f} ({math.degrees(math.asin(v.min())):.1f} deg)" for k, v in c.margins.items())
    )
    return out


@dataclass(frozen=True)
class Deployment:
    """One Pinocchio-route deployment, for the figures.

    Attributes:
        params: the design.
        trajectory: the deployment (joint angles in `dynamics.JOINT_ORDER`).
        spring: (n,) the R5 spring-damper torque (N m) at each step.
        reaction_times: (k,) instants (s) of the reactions.
        reactions: method ("pinocchio", "lagrange", "soc") -> k `checks.Reactions`.
        drift: stabilisation -> the drift study's run.
    """

    params: TenBarParams
    trajectory: td.Trajectory
    spring: np.ndarray
    reaction_times: np.ndarray
    reactions: dict[str, list[tc.Reactions]]
    drift: dict[str, td.Trajectory]


def deployment(
    mech: Mechanism, dt: float = 0.005, t_end: float | None = None, reaction_instants: int = 100
) -> Deployment:
    """The deployment (fixed step dt s, up to t_end s, default the whole), the reactions at about
    `reaction_instants` instants, and the drift study.

    Args:
        mech: the ten-bar.
        dt: step, s.
        t_end: end time, s (default: the whole deployment).
        reaction_instants: about how many instants of the reactions.

    Returns:
        The trajectory, the reactions along it, and the drift runs.
    """
    run = td.PinocchioDeployment(mech)
    traj = td.deploy(run, mech.home_q, dt, t_end)
    spring = np.array([run.spring_torque(q, v) for q, v in zip(traj.q, traj.v)])
    times, results = tc.reactions_along(mech, traj, max(1, len(traj.t) // reaction_instants))
    return Deployment(mech.params, traj, spring, times, results, drift_runs(mech))


def deployment_lines(d: Deployment) -> list[str]:
    """What the figures show, in numbers: the span, the rocker's range, the motor torques, the drift.

    Args:
        d: the deployment study.

    Returns:
        Text lines.
    """
    a = d.trajectory
    rocker = np.degrees(a.angles[:, td.JOINT_ORDER.index(tp.PASSIVE)])
    torques = ", ".join(f"{j} up to {np.abs(a.torques[:, k]).max():.3f} N m" for k, j in enumerate(tp.MOTORS))
    return [
        (
            f"deployment 0..{a.t[-1]:g} s, {len(a.t) - 1} steps; rocker R5 {rocker.min():.2f}..{rocker.max():.2f} deg; "
            f"motor torques {torques}"
        ),
        *(f"drift, {label}: closure residual max {run.residual.max():.2e} m" for label, run in d.drift.items()),
    ]
