"""The 9RR-12URU's fold in orbit: the paper's 200 s fold law prescribed on its seven drives, the truss on a
floating bus with no gravity, beside the same fold on the ground (fixed base, 1 g).

Read from the runs: the bus's attitude change and rate at the end, the whole system's momentum drift
(`mechkit.bases.momentum`) and the drives' efforts in orbit and on the ground.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pinocchio as pin

from mechkit.bases.carrier import FLOATING_JOINT, with_base
from mechkit.bases.momentum import momentum
from mechkit.mechanism import Mechanism
from mechkit.mechanisms.truss.drives import drive_state
from mechkit.mechanisms.truss.fold import apexes
from mechkit.mechanisms.truss.joint_state import drive_inputs

#: The bus: mass (kg) and principal inertias (kg m^2) (ours: the ten-bar's bus).
BUS = (100.0, (15.0, 15.0, 12.0))


@dataclass(frozen=True)
class OrbitFold:
    """The fold in orbit and on the ground.

    Attributes:
        floating: the truss on its bus.
        orbit: the floating run (`mechkit.simulation.SimulationResult`).
        ground: the fixed-base run under 1 g.
        attitude: the bus's rotation from its start at the end (rad).
        displacement: the bus's translation from its start at the end (m): the truss's centre of mass moves.
        rate: the bus's angular rate at the end (rad/s).
        momentum: the floating run's momentum drift (`MomentumHistory.drift`) and "scale" (kg m/s).
        peak_efforts: drive -> (max |effort| in orbit, on the ground) (N m).
    """

    floating: Mechanism
    orbit: Any
    ground: Any
    attitude: float
    displacement: float
    rate: float
    momentum: dict[str, float]
    peak_efforts: dict[str, tuple[float, float]]


def fold_law(mech: Mechanism) -> Callable[[float], tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """The paper's fold (`mechkit.mechanisms.truss.drives`) on the mechanism's drives, as an input law.

    Args:
        mech: `deployable_9rr12uru` (or `tetra_3rr3uru`) on any base.

    Returns:
        t (s, in [0, 200]) -> (angles rad, rates rad/s, accelerations rad/s^2) of `mech.actuated`, in order.
    """
    units, drives = apexes(mech), list(mech.actuated)

    def law(t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        values = drive_inputs(mech.params, drive_state(t), mech.actuated, units)
        return tuple(np.array([x[j] for j in drives]) for x in values)

    return law


def fold_in_orbit(mechanism: Mechanism, bus: tuple = BUS, duration: float = 200.0, rtol: float = 1e-8) -> OrbitFold:
    """The fold on a floating bus with no gravity, and on the ground under the model's gravity.

    Args:
        mechanism: `deployable_9rr12uru` on its fixed ground.
        bus: the bus's (mass kg, (Ixx, Iyy, Izz) kg m^2).
        duration: how much of the fold (s, <= 200).
        rtol: the integrator's relative tolerance (atol rtol / 100; "kkt" dynamics).

    Returns:
        The `OrbitFold`.
    """
    floating = with_base(mechanism, "floating", base_inertia=bus, gravity=(0.0, 0.0, 0.0))
    runs = {}
    for name, m in (("orbit", floating), ("ground", mechanism)):
        options = {"inputs": fold_law(m), "input_names": list(m.actuated), "dynamics": "kkt"}
        runs[name] = m.simulate(duration, rtol=rtol, atol=rtol * 1e-2, reactions=False, **options)
    orbit = runs["orbit"]
    k, kv = floating.q_index(FLOATING_JOINT), floating.v_index(FLOATING_JOINT)
    start, end = (pin.Quaternion(orbit.motion.q[i, k + 3 : k + 7]).matrix() for i in (0, -1))
    history = momentum(floating, orbit.t, orbit.motion.q, orbit.motion.v)
    peaks = {
        j: (float(np.abs(orbit.motion.effort(j)).max()), float(np.abs(runs["ground"].motion.effort(j)).max()))
        for j in mechanism.actuated
    }
    return OrbitFold(
        floating,
        orbit,
        runs["ground"],
        float(np.linalg.norm(pin.log3(end @ start.T))),
        float(np.linalg.norm(orbit.motion.q[-1, k : k + 3] - orbit.motion.q[0, k : k + 3])),
        float(np.linalg.norm(orbit.motion.v[-1, kv + 3 : kv + 6])),
        {**history.drift(), "scale": history.scale},
        peaks,
    )


def orbit_study(mechanism: Mechanism) -> dict:
    """`fold_in_orbit` over the whole fold (the ground run takes minutes), with the floating truss's motion to draw.

    Args:
        mechanism: `deployable_9rr12uru` on its fixed ground.

    Returns:
        "fold": the `OrbitFold`; "snapshot": (the truss on its bus, q (N, nq) in orbit, figure name).
    """
    fold = fold_in_orbit(mechanism)
    return {"fold": fold, "snapshot": (fold.floating, fold.orbit.motion.q, "bases_9rr12uru_orbit_snapshot")}


def orbit_lines(data: dict) -> list[str]:
    """The fold's numbers in orbit: the bus's attitude, shift and rate at the end, the momentum drift, the drives.

    Args:
        data: `orbit_study`'s data.

    Returns:
        The lines.
    """
    fold = data["fold"]
    turned = f"turned {fold.attitude:.2g} rad, shifted {fold.displacement:.3g} m, rate {fold.rate:.2g} rad/s"
    lines = [f"bus at the end: {turned}", f"momentum drift: {fold.momentum}"]
    return lines + [
        f"{j}: peak {o:.3g} N m in orbit, {g:.3g} N m on the ground" for j, (o, g) in fold.peak_efforts.items()
    ]


def orbit_figures(data: dict, folder: Path) -> list[Path]:
    """The drives' efforts in orbit beside the ground (`mechkit.bases.chart.efforts_chart`) in `folder`.

    Args:
        data: `orbit_study`'s data.
        folder: where the PNG goes.

    Returns:
        The file written.
    """
    from mechkit.bases.chart import efforts_chart

    fold = data["fold"]
    runs = {"orbit": fold.orbit.motion, "ground, 1 g": fold.ground.motion}
    path = folder / "bases_9rr12uru_orbit.png"
    return [efforts_chart(runs, list(fold.peak_efforts), path, "9RR-12URU fold in orbit")]
