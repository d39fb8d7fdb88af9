"""Speed of a motion study along a motion law a mechanism declares (`MechanismSpec.motion_laws`; by
default the 2T1R's paper law in 501 samples: assembly, velocities, accelerations, efforts
and every reaction), against the 50 ms goal, split into its phases and set beside one raw
`pin.constraintDynamics` per sample, all measured in one process.

Nothing here prints: `motion_law_speed` returns the figures, `lines` formats them
(`tools/motion_speed.py` prints them).
"""

from __future__ import annotations

import gc
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from mechkit.bench.raw import raw_constraint_dynamics
from mechkit.loading import load
from mechkit.mechanism import Mechanism
from mechkit.motion.inputs import from_law
from mechkit.motion.path import PathKinematics
from mechkit.motion.study import driven_model, inverse_batch, kinematics_along, study

#: The issue's goal for a motion study (the 2T1R motion law, 501 samples), s.
GOAL_S = 0.050


@dataclass(frozen=True)
class MotionSpeed:
    """Fastest of the repeats (s; the least disturbed by other load on the machine; the four timings
    alternate within each repeat): the whole study, its kinematics (closure solve, v, a, joint axes:
    `kinematics_along`) and its dynamics (efforts and every reaction), and one raw
    `pin.constraintDynamics` at the law's first sample (fastest mean of 1000 calls)."""

    name: str
    law: str
    samples: int
    repeats: int
    study_s: float
    kinematics_s: float
    dynamics_s: float
    raw_constraint_dynamics_s: float


def _best_times(fns: list[Callable[[], object]], repeats: int) -> list[float]:
    """Fastest time (s) of each function, the functions alternated within every repeat (so that load
    on the machine falls on all of them alike)."""
    best = [float("inf")] * len(fns)
    gc.disable()
    try:
        for _ in range(repeats):
            for k, fn in enumerate(fns):
                start = time.perf_counter()
                fn()
                best[k] = min(best[k], time.perf_counter() - start)
    finally:
        gc.enable()
    return best


def _raw_call(mech: Mechanism, q: np.ndarray, v: np.ndarray) -> Callable[[], object]:
    raw, tau = raw_constraint_dynamics(mech), np.zeros(mech.model.nv)
    return lambda: raw(q, v, tau)


def motion_law_speed(
    samples: int = 501, repeats: int = 5, name: str = "parallel_2t1r", law_name: str = "motion_law"
) -> MotionSpeed:
    """Time a motion study along a declared motion law (default: the 2T1R's, t in (0, 5] s, its singular
    start left out) at `samples` samples.

    Args:
        samples: samples of the law.
        repeats: timed repeats (the fastest is kept).
        name: the registered mechanism.
        law_name: the law, one of its spec's `motion_laws`.

    Returns:
        The times (s, fastest of the repeats) of the whole study, its kinematics and its dynamics, and of one raw
            constraintDynamics call.

    Raises:
        InvalidParameters: the mechanism declares no such law.
    """
    mech = load(name)
    law = from_law(mech, law_name, samples)
    result = study(mech, law)
    path = PathKinematics(mech, law.names)
    driven = driven_model(mech, law.names)
    driven_data = driven.create_data()

    def kinematics() -> None:
        kinematics_along(path, law)

    def inverse() -> None:
        inverse_batch(mech, driven, driven_data, result.q, result.v, result.a, None, False)

    raw = _raw_call(mech, result.q[0], result.v[0])
    study_s, kinematics_s, dynamics_s, raw_s = _best_times(
        [lambda: study(mech, law), kinematics, inverse, lambda: [raw() for _ in range(1000)]], repeats
    )
    return MotionSpeed(name, law_name, len(law.t), repeats, study_s, kinematics_s, dynamics_s, raw_s / 1000)


def lines(s: MotionSpeed) -> list[str]:
    """The figures as text: totals, per sample, ratios to the raw call, the goal.

    Args:
        s: the figures.

    Returns:
        Text lines.
    """
    per = {k: getattr(s, f"{k}_s") / s.samples for k in ("study", "kinematics", "dynamics")}
    raw = s.raw_constraint_dynamics_s
    out = [f"{s.name} {s.law.replace('_', ' ')}, {s.samples} samples (fastest of {s.repeats} runs in one process)"]
    for k, label in (
        ("study", "whole study (assembly, v, a, efforts, every reaction)"),
        ("kinematics", "  kinematics (closure solve from the predictor, v, a, axes)"),
        ("dynamics", "  efforts and every reaction (no determinacy)"),
    ):
        out.append(
            f"{label}: {getattr(s, f'{k}_s') * 1e3:.1f} ms, {per[k] * 1e6:.0f} us/sample, "
            f"{per[k] / raw:.0f}x one raw constraintDynamics"
        )
    out.append(f"raw pin.constraintDynamics: {raw * 1e6:.1f} us")
    verdict = "met" if s.study_s <= GOAL_S else f"NOT met ({s.study_s / GOAL_S:.0f}x over)"
    out.append(f"goal: the whole study under {GOAL_S * 1e3:.0f} ms: {verdict}")
    return out
