"""The simulator against MuJoCo on the same exported MJCF at the same step: the free motion of a
mechanism released at home under gravity, timed per step, with each side's closure error.

MuJoCo runs the exported file as written (`mechkit.export.mjcf`: stiff equality settings, its RK4,
the step the export chose; its Euler, semi-implicit, against mechkit's "SymplecticEuler") with bare
`mj_step` calls; mechkit runs `Mechanism.simulate` at that fixed step (RK45 with its error control off:
6 evaluations a step; RK4, MuJoCo's own method: 4; semi-implicit Euler: 1), projection after each step
where the drift exceeds `mechkit.simulation.DRIFT_TOL`, no reactions. Both
closure errors are mechkit's closure residual (m) of the configurations each visits: MuJoCo's qpos is
Pinocchio's q for an exported model.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mechkit.base.exceptions import MethodUnavailable
from mechkit.bench.markdown import replace_section
from mechkit.export.mjcf import to_mjcf
from mechkit.mechanism import Mechanism


@dataclass(frozen=True)
class SimulationSpeed:
    """One mechanism's row.

    Attributes:
        name: the mechanism; dt: the common step (s); steps: steps each side took.
        mujoco_us, mechkit_us: process CPU time per step (microseconds).
        mujoco_closure, mechkit_closure: largest closure residual over the run (m).
        difference: largest difference of the joint values at the common instants (rad or m).
        method: mechkit's one-step method at the fixed step.
        mujoco_method: MuJoCo's integrator ("RK4", or "Euler" against semi-implicit Euler).
    """

    name: str
    dt: float
    steps: int
    mujoco_us: float
    mechkit_us: float
    mujoco_closure: float
    mechkit_closure: float
    difference: float
    method: str = "RK45"
    mujoco_method: str = "RK4"

    @property
    def ratio(self) -> float:
        """mechkit's time per step over MuJoCo's."""
        return self.mechkit_us / self.mujoco_us


#: mechkit's fixed-step method -> MuJoCo's integrator of the same order and kind.
MUJOCO_METHOD = {"SymplecticEuler": "Euler"}


def mujoco_run(mech: Mechanism, duration: float, integrator: str = "RK4") -> tuple[float, np.ndarray, float]:
    """MuJoCo on the exported MJCF, released at home for `duration`.

    Args:
        mech: the mechanism (exported with `mechkit.export.to_mjcf`).
        duration: simulated time (s), rounded to whole MuJoCo steps.
        integrator: MuJoCo's integrator, "RK4" (the export's) or "Euler".

    Returns:
        MuJoCo's step (s), qpos at every step (steps + 1, nq), and the CPU seconds per step.

    Raises:
        MethodUnavailable: MuJoCo is not installed.
    """
    try:
        import mujoco
    except ImportError:
        raise MethodUnavailable("mujoco", "not installed: pip install 'mechkit[peers]'") from None
    model = mujoco.MjModel.from_xml_string(to_mjcf(mech))
    model.opt.integrator = {"RK4": mujoco.mjtIntegrator.mjINT_RK4, "Euler": mujoco.mjtIntegrator.mjINT_EULER}[
        integrator
    ]
    data = mujoco.MjData(model)
    data.qpos[:] = mech.home_q
    mujoco.mj_forward(model, data)
    dt = float(model.opt.timestep)
    steps = round(duration / dt)
    qpos = np.empty((steps + 1, model.nq))
    qpos[0] = data.qpos
    start = time.process_time()
    for k in range(steps):
        mujoco.mj_step(model, data)
        qpos[k + 1] = data.qpos
    return dt, qpos, (time.process_time() - start) / steps


def simulation_speed(mech: Mechanism, duration: float = 0.1, method: str = "RK45", repeats: int = 3) -> SimulationSpeed:
    """Both simulators on the free motion of `mech` at MuJoCo's step (see the module docstring).

    Args:
        mech: the mechanism.
        duration: simulated time (s).
        method: mechkit's one-step method ("RK45" with its error control off, "RK4", "SymplecticEuler", ...).
        repeats: timed runs of each side, interleaved; the fastest of each is kept.

    Returns:
        The row: step times, both closure errors, the largest joint difference.
    """
    mj_method = MUJOCO_METHOD.get(method, "RK4")
    dt, qpos, _ = mujoco_run(mech, duration, mj_method)
    options = {"dt": dt, "method": method, "reactions": False, "limits": None}
    mech.simulate(2 * dt, **options)  # warm: imports and first-call caches out of the timing
    mj_seconds = ours = np.inf
    for _ in range(repeats):  # interleaved, the fastest of each (a shared machine's load comes and goes)
        mj_seconds = min(mj_seconds, mujoco_run(mech, duration, mj_method)[2])
        start = time.process_time()
        result = mech.simulate((len(qpos) - 1) * dt, **options)  # MuJoCo's instants exactly
        ours = min(ours, (time.process_time() - start) / max(result.integrator["steps"], 1))
    mj_closure = max(float(np.max(np.abs(mech.closure_residual(q)))) for q in qpos[:: max(1, len(qpos) // 200)])
    difference = float(np.max(np.abs(qpos - result.motion.q)))
    return SimulationSpeed(
        mech.spec.name,
        dt,
        result.integrator["steps"],
        mj_seconds * 1e6,
        ours * 1e6,
        mj_closure,
        float(result.residual.max()),
        difference,
        method,
        mj_method,
    )


#: The small mechanisms of the speed goal (within 3x MuJoCo's step time).
SMALL = ("four_bar", "five_bar", "ten_bar")
#: Heading of the section in docs/benchmarks.md.
HEADING = "## Simulation against MuJoCo"


def markdown(rows: list[SimulationSpeed], machine: str = "2 cores, other work running") -> str:
    """The section: one row per mechanism (step times, their ratio, both closure errors, the difference).

    Args:
        rows: what `simulation_speed` gave, one per mechanism.
        machine: how the machine was loaded during the run (said in the text).

    Returns:
        The section's markdown text, heading first.
    """
    lines = [
        HEADING,
        "",
        (
            "Free motion released at home under gravity, MuJoCo on the exported MJCF (stiff equality settings, "
            "its RK4, or its semi-implicit Euler beside mechkit's; bare `mj_step`) and `Mechanism.simulate` at the "
            "same fixed step (RK45 with its error control off, 6 evaluations a step; RK4, MuJoCo's own method, 4; "
            "SymplecticEuler, 1; the position projection where the drift exceeds 1e-11 m, the velocity projection "
            "after every step; `mechkit.bench.simulation_speed`). Goal: within 3x MuJoCo's step time at the same "
            "order (RK4) with 1e-10 m closure. The cost of a step, what it is made of and what it was before: "
            "[simulation.md](simulation.md#the-cost-of-a-step). The ratios are measured in one run on this machine "
            f"({machine}), each side's time the process CPU time of the fastest of three interleaved runs."
        ),
        "",
        (
            "| mechanism | mechkit method (MuJoCo's) | step (s) | steps | MuJoCo us/step | mechkit us/step | ratio | "
            "MuJoCo closure (m) | mechkit closure (m) | max joint difference |"
        ),
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    lines += [
        f"| {r.name} | {r.method} ({r.mujoco_method}) | {r.dt:.3g} | {r.steps} | {r.mujoco_us:.1f} | "
        f"{r.mechkit_us:.0f} | {r.ratio:.0f} | {r.mujoco_closure:.2g} | {r.mechkit_closure:.2g} | {r.difference:.2g} |"
        for r in rows
    ]
    return "\n".join(lines) + "\n"


def write_section(path: str | Path, rows: list[SimulationSpeed], machine: str = "2 cores, other work running") -> None:
    """Put the section into a Markdown file: in place of its former text, else at the end.

    Args:
        path: the Markdown file, rewritten in place.
        rows: what `simulation_speed` gave, one per mechanism.
        machine: how the machine was loaded during the run (said in the text).
    """
    replace_section(path, HEADING, markdown(rows, machine))
