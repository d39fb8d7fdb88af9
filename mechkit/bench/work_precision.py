"""Work-precision: error against CPU time per simulated second, for mechkit's integrators across
tolerances and steps and for MuJoCo's across timesteps and equality settings, on the same free motion.

The motion: the mechanism released at rest at home under gravity for `DURATION` s. The reference: mechkit
with DOP853 at rtol 1e-13 (`reference`). The error of a run: the largest joint difference (rad or m) from
the reference at the end of the horizon (every run ends there exactly: MuJoCo's timesteps divide it),
its closure error the largest closure residual (m) over the run (MuJoCo's qpos is Pinocchio's q for an
exported model), its cost the process CPU time of the run over the simulated time (MuJoCo: the bare
`mj_step` loop; mechkit: `Mechanism.simulate` without reactions, warm).

A `Problem` is a mechanism and MuJoCo's model of it: the exported MJCF of a registered mechanism
(`mechkit.export.to_mjcf`: its stiff equality settings, or MuJoCo's defaults `MUJOCO_DEFAULT`), or the
field robot's own file read by both (`mechkit.bench.work_precision_gripper`: the file's settings or the
export's stiff rule). MuJoCo runs it with its timestep and integrator replaced, contacts and joint limits
disabled (mechkit runs without limits).
"""

from __future__ import annotations

import tempfile
import time
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from mechkit.base.exceptions import MethodUnavailable
from mechkit.base.plotting import pyplot, save_figure
from mechkit.bench import work_precision_gripper as gripper
from mechkit.bench.markdown import replace_section
from mechkit.bench.work_precision_energy import mechkit_energy_error, mujoco_energy_error
from mechkit.export.mjcf import to_mjcf
from mechkit.loading import load
from mechkit.mechanism import Mechanism

#: The mechanisms charted by default.
PROBLEMS = ("four_bar", "five_bar", "ten_bar")
#: Simulated time of every run (s; ours: a few swings of the registered linkages).
DURATION = 1.0
#: mechkit's settings: (method, rtol) adaptive, (method, dt) fixed.
MECHKIT_ADAPTIVE = tuple(
    (method, rtol)
    for method, rtols in (("RK45", (1e-5, 1e-6, 1e-8, 1e-10)), ("DOP853", (1e-5, 1e-7, 1e-9, 1e-11)))
    for rtol in rtols
)
MECHKIT_FIXED = (("RK4", 4e-3), ("RK4", 2e-3), ("RK4", 1e-3), ("RK4", 5e-4))
#: Same order, same fixed step: mechkit's method -> MuJoCo's (the per-step goal: within `SAME_STEP_GOAL`x).
SAME_STEP = {"RK4": "rk4"}
SAME_STEP_GOAL = 3.0
#: MuJoCo's integrators and timesteps (s; from its default 0.002 down).
MUJOCO = (("RK4", "EULER", "IMPLICITFAST"), (2e-3, 1e-3, 5e-4, 2e-4, 1e-4))
#: Evaluations of the dynamics per MuJoCo step (its integrators' stages).
MUJOCO_STAGES = {"RK4": 4, "EULER": 1, "IMPLICITFAST": 1}
#: MuJoCo's default equality settings (solref, solimp) (its documentation; `mjModel.eq_solref`, `eq_solimp`).
MUJOCO_DEFAULT = ([0.02, 1.0], [0.9, 0.95, 0.001, 0.5, 2.0])


@dataclass(frozen=True)
class Problem:
    """A mechanism and MuJoCo's model of it.

    Attributes:
        name: its name on the page.
        mech: the mechanism.
        xml: MuJoCo's MJCF text of it.
        equality: label -> (solref, solimp) for every equality, or None: as `xml` writes them.
        options: `Mechanism.simulate`'s options of every mechkit run (e.g. the file's `source`).
        notes: lines the page states about the model.
    """

    name: str
    mech: Mechanism
    xml: str
    equality: Mapping[str, Any] = field(default_factory=lambda: {"stiff": None})
    options: Mapping[str, Any] = field(default_factory=dict)
    notes: tuple[str, ...] = ()


@dataclass(frozen=True)
class Point:
    """One run.

    Attributes:
        code: "mechkit" or "MuJoCo"; method: its integrator; setting: "rtol 1e-09" or "dt 0.001".
        error: largest joint difference from the reference at the end (rad or m).
        closure: largest closure residual over the run (m).
        cpu: CPU time per simulated second (s/s).
        evaluations: evaluations of the dynamics per simulated second (MuJoCo: steps times its integrator's
            stages; 0: not counted).
        energy: the energy balance's relative drift (`work_precision_energy`; nan: not measured).
    """

    code: str
    method: str
    setting: str
    error: float
    closure: float
    cpu: float
    evaluations: float = 0.0
    energy: float = float("nan")


def reference(mech: Mechanism, duration: float = DURATION, options: Mapping[str, Any] | None = None) -> np.ndarray:
    """The reference end configuration: DOP853 at rtol 1e-13, atol 1e-14.

    Args:
        mech: the mechanism, released at rest at home.
        duration: simulated time (s).
        options: further options of `Mechanism.simulate` (e.g. `source`).

    Returns:
        (nq,) the configuration at the end.
    """
    common = {"reactions": False, "limits": None, **(options or {})}
    return mech.simulate(duration, method="DOP853", rtol=1e-13, atol=1e-14, **common).motion.q[-1]


def mechkit_points(
    mech: Mechanism, q_end: np.ndarray, duration: float = DURATION, options: Mapping[str, Any] | None = None
) -> list[Point]:
    """mechkit's runs at every setting of `MECHKIT_ADAPTIVE` and `MECHKIT_FIXED`.

    Args:
        mech: the mechanism.
        q_end: (nq,) the reference end configuration.
        duration: simulated time (s).
        options: further options of `Mechanism.simulate` (e.g. `source`).

    Returns:
        One point per setting.
    """
    runs = [(m, f"rtol {r:g}", {"rtol": r, "atol": r * 1e-2}) for m, r in MECHKIT_ADAPTIVE]
    runs += [(m, f"dt {dt:g}", {"dt": dt}) for m, dt in MECHKIT_FIXED]
    out, common = [], {"reactions": False, "limits": None, **(options or {})}
    mech.simulate(0.01, **common)  # warm
    for method, setting, step in runs:
        start = time.process_time()
        run = mech.simulate(duration, method=method, **common, **step)
        cpu = (time.process_time() - start) / duration
        error, evaluations = float(np.max(np.abs(run.motion.q[-1] - q_end))), run.integrator["evaluations"] / duration
        closure, energy = float(run.residual.max()), mechkit_energy_error(run)
        out.append(Point("mechkit", method, setting, error, closure, cpu, evaluations, energy))
    return out


def mujoco_points(
    mech: Mechanism,
    q_end: np.ndarray,
    duration: float = DURATION,
    xml: str | None = None,
    equality: Mapping[str, Any] | None = None,
) -> list[Point]:
    """MuJoCo's runs at every equality setting, integrator and timestep of `MUJOCO`.

    Args:
        mech: the mechanism.
        q_end: (nq,) the reference end configuration.
        duration: simulated time (s), a whole number of every timestep.
        xml: MuJoCo's MJCF text of the mechanism (default: its export).
        equality: label -> (solref, solimp) or None: as written (default: {"stiff": None}).

    Returns:
        One point per setting, integrator and timestep (method "<integrator> <label>").

    Raises:
        MethodUnavailable: MuJoCo is not installed, or the mechanism has no MJCF counterpart.
    """
    try:
        import mujoco
    except ImportError:
        raise MethodUnavailable("mujoco", "not installed: pip install 'mechkit[peers]'") from None
    xml, out = xml or to_mjcf(mech), []
    for (label, setting), integrator in ((e, i) for e in (equality or {"stiff": None}).items() for i in MUJOCO[0]):
        for dt in MUJOCO[1]:
            model = gripper.mujoco_model(xml, setting)
            model.opt.timestep, model.opt.integrator = dt, getattr(mujoco.mjtIntegrator, f"mjINT_{integrator}")
            data = mujoco.MjData(model)
            data.qpos[:] = mech.home_q
            steps = round(duration / dt)
            visited = np.empty((steps, model.nq))
            start = time.process_time()
            for k in range(steps):
                mujoco.mj_step(model, data)
                visited[k] = data.qpos
            cpu = (time.process_time() - start) / duration
            closure = max(float(np.max(np.abs(mech.closure_residual(q)))) for q in visited[:: max(1, steps // 100)])
            error = float(np.max(np.abs(visited[-1] - q_end)))
            evaluations, energy = (
                steps * MUJOCO_STAGES[integrator] / duration,
                mujoco_energy_error(model, mech.home_q, steps),
            )
            method = f"{integrator.lower()} {label}"
            out.append(Point("MuJoCo", method, f"dt {dt:g}", error, closure, cpu, evaluations, energy))
    return out


def at_equal_accuracy(points: Iterable[Point], error: float = 1e-6, closure: float = 1e-10) -> dict[str, Point | None]:
    """Each code's cheapest run meeting the accuracy goal (None: none does).

    Args:
        points: the runs.
        error: largest joint error allowed (rad or m).
        closure: largest closure residual allowed (m).

    Returns:
        code -> its cheapest run within both bounds, or None.
    """
    best: dict[str, Point | None] = {}
    for p in points:
        best.setdefault(p.code, None)
        if p.error <= error and p.closure <= closure and (best[p.code] is None or p.cpu < best[p.code].cpu):
            best[p.code] = p
    return best


def table(points: list[Point]) -> list[str]:
    """The markdown table of the runs.

    Args:
        points: the runs.

    Returns:
        Its lines.
    """
    head = ("code", "method", "setting", "end error", "closure (m)", "energy error", "CPU s per simulated s", "evals/s")
    lines = ["| " + " | ".join(head) + " |", "|---" * len(head) + "|"]
    for p in points:
        row = (p.code, p.method, p.setting, f"{p.error:.2g}", f"{p.closure:.2g}", f"{p.energy:.2g}", f"{p.cpu:.3g}")
        lines.append("| " + " | ".join((*row, f"{p.evaluations:.0f}")) + " |")
    return lines


def figure(name: str, points: list[Point]) -> Any:
    """The work-precision chart: end error against CPU time per simulated second, log-log, a line per
    code and method, the accuracy goal as a dashed line.

    Args:
        name: the problem's name (the title).
        points: the runs.

    Returns:
        The matplotlib figure.
    """
    fig, ax = pyplot("work-precision charts").subplots(figsize=(8.4, 4.4))
    for code, method in dict.fromkeys((p.code, p.method) for p in points):
        line = sorted((p for p in points if (p.code, p.method) == (code, method)), key=lambda p: p.cpu)
        ax.loglog(
            [p.cpu for p in line],
            [max(p.error, 1e-16) for p in line],
            "o-" if code == "mechkit" else "s--",
            label=f"{code} {method}",
        )
    ax.axhline(1e-6, color="grey", linestyle=":", label="goal 1e-6")
    ax.set_xlabel("CPU time per simulated second (s/s)")
    ax.set_ylabel("joint error at the end (rad)")
    ax.set_title(f"{name}: work-precision, free motion {DURATION:g} s")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.01, 0.5))
    fig.tight_layout()
    return fig


#: Heading of the section in docs/benchmarks.md.
HEADING = "## Work-precision"


def markdown(
    problems: dict[str, list[Point]], charts: dict[str, str], notes: Mapping[str, Iterable[str]] | None = None
) -> str:
    """The section: per problem its chart, what the page states about its model, the goal's verdict and the
    table behind the chart.

    Args:
        problems: problem name -> its runs.
        charts: problem name -> the chart's path relative to the page.
        notes: problem name -> lines about its model (default: none).

    Returns:
        The section's text, heading first.
    """
    lines = [
        HEADING,
        "",
        (
            f"Free motion released at rest at home under gravity, {DURATION:g} s (`mechkit.bench.work_precision`, "
            "`python tools/work_precision.py`): the joint error at the end against mechkit's DOP853 at rtol "
            "1e-13, the closure residual over the run, and the process CPU time per simulated second. mechkit: "
            "`Mechanism.simulate` without reactions (adaptive RK45 and DOP853 across tolerances, RK4 across "
            "steps; projection after every step); MuJoCo: the exported MJCF at the export's stiff equality "
            "settings (`stiff`) and at MuJoCo's defaults (solref 0.02 s, solimp 0.9 0.95: `default`), contacts and "
            "joint limits disabled, with its RK4, Euler and implicitfast across timesteps, the bare `mj_step` loop. "
            "Goal (issue 31): at equal accuracy, trajectory error <= 1e-6 rad and closure <= 1e-10 m, mechkit's time "
            "per simulated second no more than MuJoCo's. The reference's cross-check is MuJoCo's RK4 at its finest "
            "step (the last `rk4 stiff` row): it agrees to MuJoCo's own floor, set by its soft closure (MuJoCo holds "
            "solref at >= 2 timesteps: the stiff setting acts only at the finer steps). Measured in one run on this "
            "machine (2 cores, other work running). The energy error: the balance's largest relative drift "
            "(`mechkit.bench.work_precision_energy`); evals/s: evaluations of the dynamics per simulated second. The "
            "field robot, the Robotiq 2F-85, is its Menagerie file read by both codes (below). Not charted yet: the "
            "IFToMM problems (no MJCF counterpart of their thin rods; references: tests/fixtures/iftomm/README.md)."
        ),
        "",
    ]
    for name, points in problems.items():
        both = at_equal_accuracy(points)
        joint_only = at_equal_accuracy(points, closure=np.inf)
        verdict = []
        for code in ("mechkit", "MuJoCo"):
            p, q = both.get(code), joint_only.get(code)
            met = f"{p.method} {p.setting}, {p.cpu:.3g} s/s" if p else "none meets both"
            joint = f"{q.method} {q.setting}, {q.cpu:.3g} s/s" if q else "none"
            verdict.append(f"{code}: cheapest within both bounds {met}; within the joint error alone {joint}")
        mine, theirs = both.get("mechkit"), both.get("MuJoCo")
        if mine and theirs:
            ratio = mine.cpu / theirs.cpu
            met = "met" if ratio <= 1.0 else "missed"
            verdict.append(f"within both bounds mechkit takes {ratio:.2f}x MuJoCo's time: {met} (goal <= 1x)")
        mine, theirs = joint_only.get("mechkit"), joint_only.get("MuJoCo")
        if mine and theirs:
            verdict.append(
                f"within the joint error alone mechkit takes {mine.cpu / theirs.cpu:.1f}x MuJoCo's time: "
                f"{_per_evaluation(mine)} against {_per_evaluation(theirs)}"
            )
        verdict += _same_step(points)
        lines += [f"### Work-precision: {name}", "", f"![{name} work-precision]({charts[name]})", ""]
        lines += [f"- {n}" for n in (notes or {}).get(name, ())]
        lines += [f"- {v}" for v in verdict] + [""] + table(points) + [""]
    return "\n".join(lines)


def _same_step(points: list[Point]) -> list[str]:
    out = []
    for mine, theirs in SAME_STEP.items():
        pairs = [(p, q) for p in points if p.method == mine for q in points if q.method.split()[0] == theirs]
        pairs = [(p, q) for p, q in pairs if p.setting == q.setting]
        if pairs:
            p, q = pairs[0]
            ratio, met = p.cpu / q.cpu, "met" if p.cpu <= SAME_STEP_GOAL * q.cpu else "missed"
            out.append(
                f"same step and order ({p.setting}): mechkit {mine} takes {ratio:.0f}x MuJoCo's {q.method}: "
                f"{met} (goal <= {SAME_STEP_GOAL:g}x)"
            )
    return out


def _per_evaluation(p: Point) -> str:
    if not p.evaluations:
        return "evaluations not counted"
    return f"{p.evaluations:.0f} evaluations per simulated s at {1e6 * p.cpu / p.evaluations:.3g} us each"


def exported(name: str) -> Problem:
    """A registered mechanism and its exported MJCF, at the export's stiff settings and MuJoCo's defaults.

    Args:
        name: a registered mechanism (or a description file).

    Returns:
        The problem.
    """
    mech = load(name)
    return Problem(name, mech, to_mjcf(mech), {"stiff": None, "default": MUJOCO_DEFAULT})


def field_robot(fixtures: Path, folder: Path) -> Problem:
    """The Robotiq 2F-85 (`work_precision_gripper.case`).

    Args:
        fixtures: the repository's tests/fixtures/field folder.
        folder: an existing folder for the stripped copy (it must outlast the runs: they read it).

    Returns:
        The problem.
    """
    return Problem("robotiq_2f85", *gripper.case(fixtures, folder))


def write_section(docs: Path, names: Iterable[str], field_robots: bool = True) -> None:
    """Measure every mechanism named (and the field robot), write its chart docs/figures/work_precision_<name>.png
    and the section `HEADING` of docs/benchmarks.md (in place of its former text, else at the end).

    Args:
        docs: the docs folder (the repository's: the field robot's file is in its tests/fixtures/field).
        names: registered mechanisms (or description files) to measure.
        field_robots: also measure the Robotiq 2F-85 (`field_robot`).
    """
    problems, charts, notes = {}, {}, {}
    with tempfile.TemporaryDirectory() as folder:
        cases = [exported(name) for name in names]
        cases += [field_robot(docs.parent / "tests" / "fixtures" / "field", Path(folder))] if field_robots else []
        for case in cases:
            q_end = reference(case.mech, options=case.options)
            problems[case.name] = mechkit_points(case.mech, q_end, options=case.options) + mujoco_points(
                case.mech, q_end, xml=case.xml, equality=case.equality
            )
            charts[case.name], notes[case.name] = f"figures/work_precision_{case.name}.png", case.notes
            save_figure(figure(case.name, problems[case.name]), docs / charts[case.name])
    replace_section(docs / "benchmarks.md", HEADING, markdown(problems, charts, notes))
