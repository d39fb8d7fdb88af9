"""The IFToMM spatial slider-crank (tests/fixtures/iftomm/spatial_slider_crank.urdf) over 5 s from the crank at
6 rad/s: the slider's position by mechkit against the reference history published for the problem (M. González's,
tests/fixtures/iftomm/exudyn/slider_crank_gonzalez.csv) and against mechkit's own run at a tight tolerance, and
MuJoCo on the exported model beside it.

mechkit's positions between its steps come from a cubic Hermite interpolation of the recorded positions and
velocities (error of order h^4, far below the differences measured); MuJoCo's steps are 1 ms or less apart and
interpolated linearly.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from scipy.interpolate import CubicHermiteSpline

from mechkit.base.exceptions import MethodUnavailable
from mechkit.bench import iftomm
from mechkit.bench.markdown import replace_section
from mechkit.loading import load
from mechkit.simulation.initial import rates_velocity

FIXTURES = Path(__file__).resolve().parents[2] / "tests" / "fixtures" / "iftomm"
MODEL = FIXTURES / "spatial_slider_crank.urdf"
REFERENCE = FIXTURES / "exudyn" / "slider_crank_gonzalez.csv"
HEADING = "## The spatial slider-crank"
#: The crank's rate at t = 0 (rad/s) and the run's length (s), as the problem states them (Exudyn's files).
CRANK_RATE, DURATION = 6.0, 5.0
#: mechkit's converged run: DOP853 at this rtol (atol 1e-2 of it), checked against itself at `LOOSER`.
TIGHT, LOOSER = 1e-13, 1e-11


@dataclass(frozen=True)
class SliderCrankResult:
    """The slider's position by each code against the published history.

    Attributes:
        error: mechkit at its defaults against the published history, largest over its samples (m).
        cpu: mechkit's CPU time at its defaults (s).
        steps: its steps.
        converged: mechkit at `TIGHT` against the published history (m).
        self_check: mechkit at `TIGHT` against itself at `LOOSER` (m).
        energy: the default run's energy-balance drift relative to the energy exchanged.
        mujoco: MuJoCo's error against the history and against mechkit's converged run (m), its CPU (s) and
            steps, or why it did not run (its cross given `iftomm.MJ_AXIAL` of mass, ours).
    """

    error: float
    cpu: float
    steps: int
    converged: float
    self_check: float
    energy: float
    mujoco: str


def reference() -> np.ndarray:
    """(k, 2) the published history: time (s), slider position (m)."""
    return np.loadtxt(REFERENCE, delimiter=",", comments="#")


def slider_at(mech: Any, run: Any, t: np.ndarray) -> np.ndarray:
    """The slider's position (m) of a mechkit run at times t (s), by cubic Hermite interpolation.

    Args:
        mech: the mechanism.
        run: its `SimulationResult`.
        t: (k,) times within the run (s).

    Returns:
        (k,) positions (m).
    """
    q, v = run.motion.q[:, mech.q_index("slider")], run.motion.v[:, mech.v_index("slider")]
    return CubicHermiteSpline(run.motion.t, q, v)(t)


def measure(duration: float = DURATION) -> SliderCrankResult:
    """Run mechkit (defaults, then DOP853 at `TIGHT` and `LOOSER`) and MuJoCo, each against the published history.

    Args:
        duration: simulated time (s, <= 5: the history's length).

    Returns:
        The `SliderCrankResult`.
    """
    mech = load(str(MODEL))
    v0 = rates_velocity(mech, {"crank": CRANK_RATE}, mech.home_q)
    ref = reference()
    ref = ref[ref[:, 0] <= duration + 1e-12]
    start = time.process_time()
    run = mech.simulate(duration, v0=v0, reactions=False, limits=None)
    cpu = time.process_time() - start
    tight, looser = (
        mech.simulate(duration, v0=v0, reactions=False, limits=None, method="DOP853", rtol=r, atol=1e-2 * r)
        for r in (TIGHT, LOOSER)
    )
    x, x_tight, x_looser = (slider_at(mech, r, ref[:, 0]) for r in (run, tight, looser))
    return SliderCrankResult(
        float(np.max(np.abs(x - ref[:, 1]))),
        cpu,
        len(run.motion.t) - 1,
        float(np.max(np.abs(x_tight - ref[:, 1]))),
        float(np.max(np.abs(x_tight - x_looser))),
        float(run.energy_error / run.energy_scale),
        _mujoco(mech, duration, v0, ref, x_tight),
    )


def _mujoco(mech: Any, duration: float, v0: np.ndarray, ref: np.ndarray, x_tight: np.ndarray) -> str:
    """MuJoCo's error against the history and against mechkit's converged run (m), CPU and steps, or why it
    could not run."""
    try:
        t, q, cpu = iftomm.mujoco_run(mech, duration, v0)
    except MethodUnavailable as err:
        return f"not run: {err}"
    x = np.interp(ref[:, 0], t, q[:, mech.q_index("slider")])
    return (
        f"{np.max(np.abs(x - ref[:, 1])):.1e} m (from mechkit's converged run: {np.max(np.abs(x - x_tight)):.1e} m), "
        f"{cpu:.3f} s ({len(t) - 1} steps)"
    )


def lines(r: SliderCrankResult) -> list[str]:
    """The section's Markdown.

    Args:
        r: the measured result.

    Returns:
        Its lines.
    """

    def verdict(error: float) -> str:
        return "met" if error <= iftomm.HIGH_PRECISION else "missed"

    defaults = f"mechkit, defaults (RK45, rtol 1e-9): {r.steps} steps, energy drift {r.energy:.1e} of the exchanged"
    tight = f"mechkit, DOP853 at rtol {TIGHT:g} (against itself at {LOOSER:g}: {r.self_check:.1e} m)"
    return [
        "| run | slider position error against the published history (m) | <= 1e-3 | CPU |",
        "|---|---|---|---|",
        f"| {defaults} | {r.error:.1e} | {verdict(r.error)} | {r.cpu:.2f} s |",
        f"| {tight} | {r.converged:.1e} | {verdict(r.converged)} | |",
        f"| MuJoCo on the exported model (RK4 at its step) | {r.mujoco} | | |",
    ]


def write_section(docs: Path) -> SliderCrankResult:
    """Measure and write the section `HEADING` of docs/iftomm_benchmarks.md.

    Args:
        docs: the docs folder.

    Returns:
        The result written.
    """
    r = measure()
    intro = (
        "The slider's position over 5 s from the crank at 6 rad/s, against the history published for the problem "
        "(M. González's; tests/fixtures/iftomm/exudyn); this machine, CPU time of the run:"
    )
    replace_section(docs / "iftomm_benchmarks.md", HEADING, "\n".join([HEADING, "", intro, "", *lines(r)]) + "\n")
    return r
