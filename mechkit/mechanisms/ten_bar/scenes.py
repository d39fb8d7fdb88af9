"""The ten-bar's scenes: the deployment, stowed to deployed, for animations and the gallery, and as an
input law for motion studies."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mechkit.catalog.contract import SampledLaw
from mechkit.mechanism import Mechanism
from mechkit.mechanisms.ten_bar import dynamics as td
from mechkit.mechanisms.ten_bar.params import MOTORS, PASSIVE, motor_law

#: Step (s) of the deployment the scene samples.
DEPLOY_STEP = 0.02


def _picks(steps: int, frames: int) -> np.ndarray:
    return np.linspace(0, steps, frames).round().astype(int)


def deployment_poses(mechanism: Mechanism, frames: int = 120, dt: float = DEPLOY_STEP) -> list[np.ndarray]:
    """Stowed to deployed: the constrained-ABA deployment (fixed steps of the simulator with projection,
    step dt in s) sampled at `frames` poses, for animations.

    Args:
        mechanism: the ten-bar.
        frames: how many poses.
        dt: step, s.

    Returns:
        The configurations (nq,).
    """
    trajectory = td.deploy(td.PinocchioDeployment(mechanism), mechanism.home_q, dt)
    return [trajectory.q[i] for i in _picks(len(trajectory.q) - 1, frames)]


def deployment_times(mechanism: Mechanism, poses: int, dt: float = DEPLOY_STEP) -> np.ndarray:
    """Times (s) of the deployment scene's poses (the steps it picks).

    Args:
        mechanism: the ten-bar.
        poses: the number of poses.
        dt: step, s.

    Returns:
        (poses,) times, s.
    """
    return dt * _picks(round(mechanism.params.deploy_time / dt), poses)


def deployment_law(mechanism: Mechanism, samples: int | None = None) -> SampledLaw:
    """The deployment as an input law of the motors and the rocker R5: every step (dt =
    `DEPLOY_STEP`), or `samples` poses, each pose a warm start (`SPEC.motion_laws["deploy"]`).

    Args:
        mechanism: the ten-bar.
        samples: how many poses (default: every step).

    Returns:
        The law on R1, R3, R5 with the poses as guesses.
    """
    every_step = round(mechanism.params.deploy_time / DEPLOY_STEP) + 1
    frames = samples or every_step
    poses = np.array(deployment_poses(mechanism, frames))
    joints = (*MOTORS, PASSIVE)
    return SampledLaw(
        joints,
        deployment_times(mechanism, frames),
        poses[:, [mechanism.q_index(j) for j in joints]],
        guesses=poses,
        source="deployment, every step" if frames == every_step else f"deployment, {frames} poses",
    )


#: The spacecraft bus the array deploys from (ours: a 100 kg small satellite, principal moments in kg m^2).
BUS = (100.0, (15.0, 15.0, 12.0))


def in_orbit(mechanism: Mechanism, bus: tuple = BUS, rtol: float = 1e-8) -> dict:
    """The deployment in orbit on a floating bus (no gravity) beside the ground test under 1 g: the same
    motor laws (`params.motor_law`), the R5 spring, the simulator (`mechkit.bases`).

    Args:
        mechanism: the ten-bar on its fixed ground.
        bus: the bus's (mass kg, (Ixx, Iyy, Izz) kg m^2), at the ground body's origin.
        rtol: the integrator's relative tolerance.

    Returns:
        "orbit" and "ground": the `SimulationResult`s; "floating": the mechanism on the bus.
    """
    from mechkit.bases import with_base

    floating = with_base(mechanism, "floating", base_inertia=bus, gravity=(0.0, 0.0, 0.0))

    def law(t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return motor_law(mechanism.params, t)

    runs = {
        name: m.simulate(
            mechanism.params.deploy_time,
            inputs=law,
            input_names=list(MOTORS),
            dynamics="kkt",
            rtol=rtol,
            atol=rtol * 1e-2,
        )
        for name, m in (("orbit", floating), ("ground", mechanism))
    }
    return {**runs, "floating": floating}


#: Where a latch catches the spring rocker R5 (ours: reached from below by the rocker's first swing, in
#: orbit and under 1 g alike).
LATCH_R5 = -0.08


def latch_up_in_orbit(mechanism: Mechanism, bus: tuple = BUS, latch: float = LATCH_R5, rtol: float = 1e-8) -> dict:
    """The latch-up shock of the rocker R5 in orbit (floating bus, no gravity) and on the ground (1 g).

    Each run simulates to the latch, then the jump the simulator's impact takes there
    (`mechkit.simulation.events.impact`), and reads its impulses (`mechkit.bases.latch_up`).

    Args:
        mechanism: the ten-bar on its fixed ground.
        bus: the bus's (mass kg, (Ixx, Iyy, Izz) kg m^2).
        latch: R5's latched angle (rad).
        rtol: the integrator's relative tolerance.

    Returns:
        "orbit" and "ground": (latch time s, R5's rate at arrival rad/s, `LatchUp`, the simulator's
        dissipated energy J); "floating": the mechanism on the bus.
    """
    from mechkit.bases import with_base
    from mechkit.bases.latch_up import latch_up
    from mechkit.simulation import Latch
    from mechkit.simulation.events import impact

    floating = with_base(mechanism, "floating", base_inertia=bus, gravity=(0.0, 0.0, 0.0))

    def law(t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return motor_law(mechanism.params, t)

    options = {"inputs": law, "input_names": list(MOTORS), "dynamics": "kkt", "rtol": rtol, "atol": rtol * 1e-2}
    out: dict = {"floating": floating}
    for name, m in (("orbit", floating), ("ground", mechanism)):
        latched = m.simulate(
            mechanism.params.deploy_time, latches=[Latch(PASSIVE, latch, +1)], reactions=False, **options
        )
        when = next(t for t, what, _ in latched.events if what == f"latch:{PASSIVE}")
        before = m.simulate(when, reactions=False, **options)
        q, v = before.motion.q[-1], before.motion.v[-1]
        drives = np.array([m.v_index(j) for j in MOTORS])
        cm = m.closure_model
        jump = impact(cm, cm.create_data(), q, v, drives, law(when)[1], m.v_index(PASSIVE), 0.0)
        shock = latch_up(m, q, v, jump.v, [*MOTORS, PASSIVE])
        out[name] = (when, float(v[m.v_index(PASSIVE)]), shock, jump.dissipated)
    return out


def orbit_study(mechanism: Mechanism) -> dict:
    """`in_orbit` with the floating mechanism's motion to draw.

    Args:
        mechanism: the ten-bar on its fixed ground.

    Returns:
        `in_orbit`'s runs and "snapshot": (the ten-bar on its bus, q (N, nq) in orbit, figure name).
    """
    runs = in_orbit(mechanism)
    return {**runs, "snapshot": (runs["floating"], runs["orbit"].motion.q, "bases_ten_bar_orbit_snapshot")}


def orbit_lines(data: dict) -> list[str]:
    """The orbit study's numbers: each motor's torque range in orbit and on the ground, the bus's momentum drift.

    Args:
        data: `orbit_study`'s data.

    Returns:
        The lines.
    """
    from mechkit.bases import momentum

    orbit, ground = data["orbit"], data["ground"]
    lines = [
        f"{j}: {orbit.motion.effort(j).min():.4g} .. {orbit.motion.effort(j).max():.4g} N m in orbit, "
        f"{ground.motion.effort(j).min():.4g} .. {ground.motion.effort(j).max():.4g} N m on the ground"
        for j in MOTORS
    ]
    drift = momentum(data["floating"], orbit.t, orbit.motion.q, orbit.motion.v).drift()
    return [*lines, f"momentum drift in orbit: {drift}"]


def orbit_figures(data: dict, folder: Path) -> list[Path]:
    """The orbit study's chart (`mechkit.bases.chart.floating_chart`) in `folder`.

    Args:
        data: `orbit_study`'s data.
        folder: where the PNG goes.

    Returns:
        The file written.
    """
    from mechkit.bases.chart import floating_chart

    path = folder / "bases_ten_bar_orbit.png"
    return [floating_chart(data["floating"], data["orbit"], data["ground"], list(MOTORS), path, "ten-bar in orbit")]
