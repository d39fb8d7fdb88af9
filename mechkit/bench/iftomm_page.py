"""docs/iftomm_benchmarks.md: every IFToMM benchmark problem run (`mechkit.bench.iftomm`), its error against
its reference, mechkit's CPU time beside MuJoCo's on the exported model and the published ones.

Each `run_*` measures one problem on the fixtures in the repository's tests/fixtures/iftomm (the N-four-bar
with N = 40 written by `n_four_bar_urdf`) and returns its `Row`; `write_page` writes the page's table.
"""

from __future__ import annotations

import tempfile
import xml.etree.ElementTree as ET
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pinocchio as pin
import scipy.special

from mechkit.base.exceptions import InvalidArgument, MethodUnavailable
from mechkit.bench import iftomm
from mechkit.bench.markdown import replace_section
from mechkit.core import body_name
from mechkit.forces import read_described
from mechkit.loading import load

FIXTURES = Path(__file__).resolve().parents[2] / "tests" / "fixtures" / "iftomm"
HEADING = "## Measured"
#: MuJoCo's (integrator, timestep s) on the flyball governor (its struts as spatial tendons; ours).
MUJOCO_FLYBALL = (("RK4", 1e-3), ("RK4", 1e-4), ("implicitfast", 1e-4))
#: Published CPU times of the same problems (OpenSim 3.2 on an Intel Core i5-4570 at 3.2 GHz; their pages,
#: RehabEngGroup/MBSbenchmarksInOpenSim help/benchmarks/*.rst; Exudyn's from its page).
PUBLISHED = {
    "pendulum": "OpenSim 0.637 s (its 10 s), Exudyn 0.037 s",
    "n_four_bar_2": "OpenSim 0.455 s",
    "n_four_bar_40": "none found",
    "bricard": "OpenSim 0.258 s",
    "flyball": "OpenSim 0.233 s (CPodes, accuracy 1e-6)",
}


def _mujoco_cell(error: Callable[[np.ndarray, np.ndarray], float], mech, duration: float, v0=None) -> str:
    """ "error m, cpu s (steps)" of MuJoCo on the exported model, or why it could not run."""
    try:
        t, q, cpu = iftomm.mujoco_run(mech, duration, v0)
    except MethodUnavailable as err:
        return f"not run: {err}"
    return f"{error(t, q):.1e} m, {cpu:.3f} s ({len(t) - 1} steps)"


def run_pendulum(duration: float = 10.0) -> iftomm.Row:
    """The simple pendulum released at rest from horizontal, against the exact elliptic-function solution.

    Args:
        duration: simulated time (s; the library's 2000 s is the slow test's).

    Returns:
        Its `Row`.
    """
    mech = load(FIXTURES / "pendulum.urdf")

    def error(t: np.ndarray, q: np.ndarray) -> float:
        sn = scipy.special.ellipj(scipy.special.ellipk(0.5) - np.sqrt(iftomm.G) * t, 0.5)[0]
        theta = 2 * np.arcsin(np.sqrt(0.5) * sn)
        return float(np.max(np.hypot(np.sin(theta) - np.cos(q[:, 0]), -np.cos(theta) - np.sin(q[:, 0]))))

    run, cpu = iftomm.timed(mech, duration)
    return iftomm.Row(
        f"simple pendulum, {duration:g} s, defaults (RK45, rtol 1e-9)", error(run.t, run.motion.q),
        "exact solution", cpu, len(run.t) - 1, _mujoco_cell(error, mech, duration), PUBLISHED["pendulum"],
    )  # fmt: skip


def four_bar_start(mech: Any, n: int) -> np.ndarray:
    """The N-four-bar's initial joint rates: cranks at -1 rad/s (B0 at +1 m/s along x), couplers at +1 rad/s.

    Args:
        mech: the N-four-bar (`mechkit.Mechanism`).
        n: its windows N.

    Returns:
        (nv,) the rates.
    """
    v0 = np.zeros(mech.model.nv)
    for k in range(n + 1):
        v0[mech.v_index(f"crank{k}")] = -1.0
    for k in range(1, n + 1):
        v0[mech.v_index(f"coupler{k}")] = 1.0
    return v0


def run_n_four_bar(n: int, duration: float) -> iftomm.Row:
    """The N-four-bar through its singular positions, B0 against the branch's one-coordinate ODE.

    Args:
        n: windows N (2: the fixture; else written by `n_four_bar_urdf`).
        duration: simulated time (s).

    Returns:
        Its `Row`.
    """
    if n == 2:
        mech = load(FIXTURES / "n_four_bar.urdf")
    else:
        with tempfile.TemporaryDirectory() as folder:
            path = Path(folder) / f"n_four_bar_{n}.urdf"
            path.write_text(iftomm.n_four_bar_urdf(n))
            mech = load(path)
    column = mech.q_index("crank0")

    def error(t: np.ndarray, q: np.ndarray) -> float:
        theta, crank = iftomm.four_bar_reference(n, t), q[:, column]
        return float(np.max(np.hypot(np.cos(crank) - np.cos(theta), np.sin(crank) - np.sin(theta))))

    v0 = four_bar_start(mech, n)
    run, cpu = iftomm.timed(mech, duration, v0=v0, limits=None)
    crossings = int(run.integrator["singular_crossings"])
    return iftomm.Row(
        f"N-four-bar N = {n}, {duration:g} s, defaults: {crossings} singular positions passed on the branch",
        error(run.t, run.motion.q), "branch ODE (B0)", cpu, len(run.t) - 1,
        _mujoco_cell(error, mech, duration, v0), PUBLISHED[f"n_four_bar_{n}"] if n in (2, 40) else "",
    )  # fmt: skip


def run_bricard(duration: float = 10.0) -> iftomm.Row:
    """Bricard's mechanism released at rest, every joint's origin against the reduced one-coordinate ODE.

    Args:
        duration: simulated time (s).

    Returns:
        Its `Row`.
    """
    mech = load(FIXTURES / "bricard.urdf")
    chart = iftomm.BricardChart(mech.model)

    def error(t: np.ndarray, q: np.ndarray) -> float:
        return iftomm.point_error(mech.model, q, chart.run(t))

    run, cpu = iftomm.timed(mech, duration, limits=None)
    return iftomm.Row(
        f"Bricard, {duration:g} s, defaults: energy drift {run.energy_error:.1e} J of {run.energy_scale:.2f} J",
        error(run.t, run.motion.q), "reduced ODE (joint origins)", cpu, len(run.t) - 1,
        _mujoco_cell(lambda t, q: error(t[::10], q[::10]), mech, duration), PUBLISHED["bricard"],
    )  # fmt: skip


def flyball_tendons(mech: Any, integrator: str, timestep: float) -> Callable[[ET.Element], None]:
    """An edit of the flyball governor's exported MJCF: its struts as MuJoCo spatial tendons between sites
    (stiffness, damping, springlength), and MuJoCo's integrator and timestep.

    Args:
        mech: the flyball governor (`mechkit.Mechanism` of tests/fixtures/iftomm/flyball_governor.urdf).
        integrator: MuJoCo's integrator ("RK4", "implicitfast", ...).
        timestep: its step (s).

    Returns:
        The edit, for `iftomm.mujoco_run`.
    """

    def edit(root: ET.Element) -> None:
        bodies = {b.get("name"): b for b in root.iter("body")}
        tendons = ET.SubElement(root, "tendon")
        for strut in read_described(None, mech.urdf, mech.model, tuple(mech.actuated)).struts:
            spatial = ET.SubElement(
                tendons, "spatial", name=strut.name, stiffness=repr(strut.stiffness), damping=repr(strut.damping),
                springlength=repr(strut.free_length),
            )  # fmt: skip
            for end, frame, point in (("a", strut.frame_a, strut.point_a), ("b", strut.frame_b, strut.point_b)):
                joint = mech.model.frames[mech.model.getFrameId(frame)].parentJoint
                body = bodies[body_name(mech.model, joint)]
                ET.SubElement(body, "site", name=f"{strut.name}_{end}", pos=" ".join(map(repr, point)))
                ET.SubElement(spatial, "site", site=f"{strut.name}_{end}")
        root.find("option").set("integrator", integrator)
        root.find("option").set("timestep", repr(timestep))

    return edit


def run_flyball(duration: float = 10.0, method: str = "Radau", rtol: float = 1e-6, mujoco: bool = True) -> iftomm.Row:
    """The stiff flyball governor, s against Pinocchio's ABA with the springs by scipy's Radau at 1e-10.

    Args:
        duration: simulated time (s).
        method: mechkit's integrator.
        rtol: its relative tolerance.
        mujoco: also run MuJoCo (`MUJOCO_FLYBALL`); else its cell points to the row that did.

    Returns:
        Its `Row`.
    """
    mech = load(FIXTURES / "flyball_governor.urdf")
    reference = iftomm.flyball_reference(pin.buildModelFromUrdf(str(FIXTURES / "flyball_governor.urdf")), duration)
    v0 = np.zeros(mech.model.nv)
    v0[mech.v_index("shaft")] = 2 * np.pi
    run, cpu = iftomm.timed(mech, duration, v0=v0, method=method, rtol=rtol, limits=None)
    s = run.motion.q[:, mech.q_index("s")]
    cells = [] if mujoco else ["as in the RK45 row"]
    for integrator, step in MUJOCO_FLYBALL if mujoco else ():
        t, q, mj_cpu = iftomm.mujoco_run(mech, duration, v0, flyball_tendons(mech, integrator, step))
        cells.append(
            f"{integrator} {step:g} s: "
            + (f"{np.max(np.abs(q[:, 3] - reference.sol(t)[2])):.1e} m, {mj_cpu:.3f} s" if np.isfinite(q).all()
               else "unstable (non-finite state)")
        )  # fmt: skip
    mujoco = "; ".join(cells)
    return iftomm.Row(
        f"flyball governor, {duration:g} s, {method} at rtol {rtol:g}",
        float(np.max(np.abs(s - reference.sol(run.t)[2]))),
        "Pinocchio ABA + Radau 1e-10 (s)", cpu, len(run.t) - 1,
        mujoco, PUBLISHED["flyball"],
    )  # fmt: skip


def _line(r: iftomm.Row) -> str:
    """One row of the page's table."""
    return (
        f"| {r.problem} | {r.error:.1e} | {r.reference} | {'met' if r.passed else 'missed'} | {r.cpu:.2f} s "
        f"({r.steps}) | {r.mujoco} | {r.published} |"
    )


def table(rows: list[iftomm.Row]) -> str:
    """The Markdown table of the rows.

    Args:
        rows: the measured problems.

    Returns:
        The table's text.
    """
    return "\n".join([TABLE_HEAD, *(_line(r) for r in rows)])


TABLE_HEAD = (
    "| problem and run | error (m) | against | <= 1e-3 | mechkit CPU (steps) | MuJoCo | published |\n"
    "|---|---|---|---|---|---|---|"
)
INTRO = (
    "This machine (2 cores shared with other work; CPU time of the run; `python tools/iftomm_benchmarks.py`, "
    "`--only KEY ...` to measure some problems again and keep the other rows):"
)
#: The page's problems in its order: key -> (how its rows' first cell starts, the runs measuring it).
PROBLEMS: dict[str, tuple[str, Callable[[], list[iftomm.Row]]]] = {
    "pendulum": ("simple pendulum", lambda: [run_pendulum()]),
    "n_four_bar_2": ("N-four-bar N = 2,", lambda: [run_n_four_bar(2, 10.0)]),
    "bricard": ("Bricard", lambda: [run_bricard()]),
    "flyball": ("flyball governor", lambda: [run_flyball(method="RK45"), run_flyball(method="Radau", mujoco=False)]),
    "n_four_bar_40": ("N-four-bar N = 40,", lambda: [run_n_four_bar(40, 20.0)]),
}


def write_page(docs: Path, slow: bool = True, only: list[str] | None = None) -> list[iftomm.Row]:
    """Measure the problems and write the section `HEADING` of docs/iftomm_benchmarks.md.

    Args:
        docs: the docs folder.
        slow: also the N = 40 four-bar's 20 s (minutes).
        only: measure these problems only (`PROBLEMS` keys), the page's rows of the others kept as they are.

    Returns:
        The rows measured.

    Raises:
        InvalidArgument: an unknown problem in `only`.
    """
    unknown = sorted(set(only or ()) - set(PROBLEMS))
    if unknown:
        raise InvalidArgument("only", unknown, f"unknown problems; expected some of {', '.join(PROBLEMS)}")
    keys = only if only is not None else [k for k in PROBLEMS if slow or k != "n_four_bar_40"]
    page = (docs / "iftomm_benchmarks.md").read_text().partition(HEADING)[2].split("\n## ")[0] if only else ""
    measured, lines = [], []
    for key, (start, runs) in PROBLEMS.items():
        if key in keys:
            rows = runs()
            measured += rows
            lines += [_line(r) for r in rows]
        else:
            lines += [line for line in page.splitlines() if line.startswith(f"| {start}")]
    body = "\n".join([TABLE_HEAD, *lines])
    text = f"{HEADING}\n\n{INTRO}\n\n{body}\n"
    replace_section(docs / "iftomm_benchmarks.md", HEADING, text)
    return measured
