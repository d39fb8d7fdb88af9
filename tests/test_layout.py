"""The package's shape: imports go down (no circle, the core never imports what sits on it), modules stay
small, the registry is lazy, every mechanism has its files, tests mirror the package, and a module name
found in several folders is one concept."""

from __future__ import annotations

import ast
import json
import subprocess
import sys
from fnmatch import fnmatch
from pathlib import Path

import mechkit
from mechkit.catalog.registry import ENTRIES, get_spec, names

PACKAGE = Path(mechkit.__file__).resolve().parent
ROOT = PACKAGE.parent
#: The bottom floors, derived from the folders: the base utilities and the numerical core.
BELOW = ("mechkit.base", "mechkit.core")
MAX_LINES = 400


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _file_of(module: str) -> Path | None:
    """The file a dotted module name is (a module or a package's __init__), if it is ours."""
    base = PACKAGE.parent.joinpath(*module.split("."))
    for candidate in (base.with_suffix(".py"), base / "__init__.py"):
        if candidate.is_file():
            return candidate
    return None


def _imports(path: Path) -> set[Path]:
    """Our files that `path` imports anywhere (module level, functions, TYPE_CHECKING blocks alike).

    `from package import name` is an edge to the submodule `package.name` when there is one, else to
    the package's __init__ (the name is then defined there).
    """
    here = _module_name(path)
    package = here if path.name == "__init__.py" else here.rpartition(".")[0]
    found: set[Path] = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join(anchor + ([base] if base else []))
            targets = []
            for alias in node.names:
                sub = f"{base}.{alias.name}"
                targets.append(sub if _file_of(sub) else base)
        else:
            continue
        for target in targets:
            if target.split(".")[0] != "mechkit":
                continue
            file = _file_of(target)
            if file is not None and file != path:
                found.add(file)
    return found


def _graph() -> dict[Path, set[Path]]:
    return {path: _imports(path) for path in sorted(PACKAGE.rglob("*.py"))}


def _strongly_connected(graph: dict[Path, set[Path]]) -> list[list[Path]]:
    """Tarjan's algorithm: the components of more than one file (import circles)."""
    index: dict[Path, int] = {}
    low: dict[Path, int] = {}
    stack: list[Path] = []
    on_stack: set[Path] = set()
    circles: list[list[Path]] = []

    def visit(v: Path) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                circles.append(component)

    for v in graph:
        if v not in index:
            visit(v)
    return circles


def _relative(paths) -> list[str]:
    return sorted(str(p.relative_to(PACKAGE.parent)) for p in paths)


def test_import_graph_has_no_circle():
    circles = _strongly_connected(_graph())
    assert not circles, "import circles: " + "; ".join(" <-> ".join(_relative(c)) for c in circles)


def _within(module: str, packages: tuple[str, ...]) -> bool:
    """Whether a module is one of the packages or inside one (mechkit.bases is not in mechkit.base)."""
    return any(module == p or module.startswith(p + ".") for p in packages)


def test_core_imports_nothing_above_it():
    """The base imports only the base; the core only the base and itself (both derived from the folders)."""
    upward = []
    for path, targets in _graph().items():
        here = _module_name(path)
        if not _within(here, BELOW):
            continue
        allowed = ("mechkit.base",) if _within(here, ("mechkit.base",)) else BELOW
        upward += [f"{here} -> {_module_name(t)}" for t in targets if not _within(_module_name(t), allowed)]
    assert not upward, upward


def _reached(graph: dict[Path, set[Path]], start: Path) -> set[Path]:
    """Every file that importing `start` runs: what it imports, directly or through others, and the face
    (`__init__.py`) of every package on the way but mechkit's own."""
    seen, todo = set(), [start]
    while todo:
        path = todo.pop()
        faces = [p / "__init__.py" for p in path.parents if PACKAGE in p.parents]
        for target in graph[path] | set(faces):
            if target not in seen:
                seen.add(target)
                todo.append(target)
    return seen


def test_the_simulator_sits_below_the_mechanism():
    """`Mechanism.simulate` and `.equilibrium` import the simulator: importing it or the history it writes
    never runs `mechanism.py` (no circle between folders, no import running back up)."""
    graph = _graph()
    mechanism = PACKAGE / "mechanism.py"
    assert any(_module_name(t).startswith("mechkit.simulation") for t in graph[mechanism])
    below = [p for p in graph if p.parent.name in ("simulation", "history")]
    assert below and not [str(p.relative_to(ROOT)) for p in below if mechanism in _reached(graph, p)]


def test_only_the_command_line_reaches_the_top_floors():
    """The bench measures the library and the command line prints it: no library module imports either
    (the second opinion once took its input joints from the bench)."""
    top = {"mechkit.bench": ("mechkit.bench", "mechkit.cli"), "mechkit.cli": ("mechkit.cli", "mechkit.__main__")}
    upward = []
    for path, targets in _graph().items():
        here = _module_name(path)
        for target in targets:
            name = _module_name(target)
            for floor, allowed in top.items():
                if name.startswith(floor) and not here.startswith(allowed):
                    upward.append(f"{here} -> {name}")
    assert not upward, upward


def _mechanism_imports(path: Path) -> list[str]:
    """The `mechkit.mechanisms...` modules a file imports anywhere (absolute imports)."""
    found = []
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        names = (
            [a.name for a in node.names]
            if isinstance(node, ast.Import)
            else [node.module or ""]
            if isinstance(node, ast.ImportFrom) and not node.level
            else []
        )
        found += [n for n in names if n == "mechkit.mechanisms" or n.startswith("mechkit.mechanisms.")]
    return found


def test_only_the_contract_leads_to_a_mechanism():
    """No module outside `mechkit/mechanisms/` (bench, sweep, motion, second opinion, viz, command line,
    ...) and no driver in `tools/` imports a mechanism package: what they need of a mechanism is a hook
    of its `MechanismSpec`, read through the registry."""
    files = [p for p in PACKAGE.rglob("*.py") if not p.is_relative_to(PACKAGE / "mechanisms")]
    files += sorted((ROOT / "tools").glob("*.py"))
    bypass = [f"{p.relative_to(ROOT)} -> {m}" for p in files for m in _mechanism_imports(p)]
    assert not bypass, bypass


def test_a_bypass_of_the_contract_is_detected(tmp_path):
    """The detector itself, on the kinds of import statement a bypass takes."""
    code = (
        "import mechkit.mechanisms.ten_bar.dynamics as td\n"
        "from mechkit.mechanisms.rocket_gimbal import resultant\n"
        "def f():\n    from mechkit.mechanisms.parallel_2t1r.motion_law import motion_law\n"
        "from mechkit.catalog.registry import get_spec\n"
    )
    (tmp_path / "m.py").write_text(code)
    assert _mechanism_imports(tmp_path / "m.py") == [
        "mechkit.mechanisms.ten_bar.dynamics",
        "mechkit.mechanisms.rocket_gimbal",
        "mechkit.mechanisms.parallel_2t1r.motion_law",
    ]


def test_no_test_runs_a_tool():
    """Tests test the library: no test imports or runs a script of `tools/` (runpy, importlib from a
    file path, or `tools` put on sys.path)."""
    running = ("run_path", "spec_from_file_location", "SourceFileLoader")
    found = []
    for path in sorted((ROOT / "tests").rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.Attribute) and node.attr in running:
                found.append(f"{path.relative_to(ROOT)}:{node.lineno} {node.attr}")
            elif isinstance(node, (ast.Import, ast.ImportFrom)):
                names = [a.name for a in node.names] if isinstance(node, ast.Import) else [node.module or ""]
                found += [
                    f"{path.relative_to(ROOT)}:{node.lineno} import {n}"
                    for n in names
                    if n.split(".")[0] == "tools" or n in ("runpy",)
                ]
    assert not found, found


def test_every_mechanism_has_its_files_and_no_file_is_orphaned():
    """Each registered mechanism has `xacro/<name>.urdf.xacro` (its spec's template), `urdf/<name>.urdf`
    and `docs/mechanisms/<name>.md`; every template, URDF and page belongs to a registered mechanism,
    and every other xacro file is a macro file some template includes."""
    registered = set(names())
    for name in registered:
        assert get_spec(name).template == f"{name}.urdf.xacro", name
    templates = {p.name.removesuffix(".urdf.xacro") for p in (ROOT / "xacro").glob("*.urdf.xacro")}
    urdfs = {p.stem for p in (ROOT / "urdf").glob("*.urdf")}
    pages = {p.stem for p in (ROOT / "docs" / "mechanisms").glob("*.md")}
    for kind, found in (
        ("xacro/<name>.urdf.xacro", templates),
        ("urdf/<name>.urdf", urdfs),
        ("docs/mechanisms/<name>.md", pages),
    ):
        assert found == registered, (
            f"{kind}: missing {sorted(registered - found)}, orphaned {sorted(found - registered)}"
        )
    texts = "".join(p.read_text() for p in (ROOT / "xacro").glob("*.xacro"))
    macros = [p.name for p in (ROOT / "xacro").glob("*.xacro") if not p.name.endswith(".urdf.xacro")]
    assert all(f"/{m}" in texts or f"'{m}'" in texts or f'"{m}"' in texts for m in macros), macros


def test_a_circle_is_detected():
    """The detector itself: a two-file circle and a self-consistent chain."""
    a, b, c = Path("a"), Path("b"), Path("c")
    assert _strongly_connected({a: {b}, b: {a}, c: {a}}) == [[b, a]]
    assert _strongly_connected({a: {b}, b: {c}, c: set()}) == []


def test_no_module_over_the_line_limit():
    long = {
        str(p.relative_to(PACKAGE.parent)): n
        for p in PACKAGE.rglob("*.py")
        if (n := len(p.read_text().splitlines())) > MAX_LINES
    }
    assert not long, f"modules over {MAX_LINES} lines: {long}"


def _modules_after(code: str) -> list[str]:
    out = subprocess.run(
        [
            sys.executable,
            "-c",
            code + "\nimport sys, json\n"
            "print(json.dumps(sorted(m for m in sys.modules if m.startswith('mechkit.mechanisms'))))",
        ],
        capture_output=True,
        text=True,
        check=True,
    )
    return json.loads(out.stdout.splitlines()[-1])


def test_listing_imports_no_mechanism():
    assert _modules_after("from mechkit.cli import main; main(['list'])") == []


def test_loading_one_mechanism_imports_no_other():
    """Shared packages (the planar-linkage references, the truss) may come along; other mechanisms may not."""
    loaded = _modules_after("import mechkit; mechkit.load('four_bar')")
    assert "mechkit.mechanisms.four_bar" in loaded
    others = [e.package for e in ENTRIES if e.name != "four_bar"]
    assert not [m for m in loaded if any(m == o or m.startswith(o + ".") for o in others)], loaded


def test_only_the_command_line_prints():
    printing = []
    for path in PACKAGE.rglob("*.py"):
        if path.is_relative_to(PACKAGE / "cli"):
            continue
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in ("print", "input"):
                printing.append(f"{path.relative_to(PACKAGE.parent)}:{node.lineno}")
    assert not printing, printing


def test_nothing_outside_the_core_imports_a_core_submodule():
    """The core's face (`mechkit/core/__init__.py`) is its contract: other modules import `mechkit.core`
    or names from it, never `mechkit.core.<module>`."""
    face = PACKAGE / "core" / "__init__.py"
    inside = []
    for path, targets in _graph().items():
        if _module_name(path).startswith("mechkit.core"):
            continue
        inside += [
            f"{_module_name(path)} -> {_module_name(t)}"
            for t in targets
            if _module_name(t).startswith("mechkit.core.") and t != face
        ]
    assert not inside, inside


#: Pinocchio's constraint API (legacy and newer): only `mechkit/core/pin_constraints.py` names it.
CONSTRAINT_API = {
    "RigidConstraintModel",
    "RigidConstraintData",
    "StdVec_RigidConstraintModel",
    "StdVec_RigidConstraintData",
    "ProximalSettings",
    "constraintDynamics",
    "initConstraintDynamics",
    "lcaba",
    "computeJointMinimalOrdering",
    "getConstraintsJacobian",
    "BaumgarteCorrectorParameters",
    "ContactType",
    "PointAnchorConstraintModel",
    "FrameAnchorConstraintModel",
    "ConstraintModel",
    "ConstraintData",
    "ConstraintCholeskyDecomposition",
    "ContactCholeskyDecomposition",
    "ADMMConstraintSolver",
    "PGSConstraintSolver",
    "contactInverseDynamics",
    "convertToRigidConstraintModel",
    "buildModelAndConstraintsFromMJCF",
    "buildModelAndLegacyConstraintsFromMJCF",
}


def _constraint_names(path: Path) -> set[str]:
    """The constraint-API names a file uses as attributes (`pin.X`) or imports (`from pinocchio import X`)."""
    found = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Attribute) and node.attr in CONSTRAINT_API:
            found.add(node.attr)
        elif isinstance(node, ast.ImportFrom) and (node.module or "").startswith("pinocchio"):
            found |= {a.name for a in node.names if a.name in CONSTRAINT_API}
    return found


def test_only_one_module_names_pinocchios_constraint_api():
    users = {_module_name(p): sorted(names) for p in sorted(PACKAGE.rglob("*.py")) if (names := _constraint_names(p))}
    assert set(users) == {"mechkit.core.pin_constraints"}, users


def test_the_constraint_api_scan_sees_attributes_and_imports(tmp_path):
    probe = tmp_path / "probe.py"
    probe.write_text("import pinocchio as pin\nfrom pinocchio import lcaba\nx = pin.constraintDynamics\n")
    assert _constraint_names(probe) == {"lcaba", "constraintDynamics"}


#: Modules without a test file at their mirrored path, and where their behaviour is tested instead.
TESTED_ELSEWHERE = {
    "mechkit/__main__.py": "`python -m mechkit` runs `mechkit.cli.main`: every subprocess test of the command line "
    "goes through it (tests/test_cli.py, tests/cli/)",
    "mechkit/base/arguments.py": (
        "the argument checks of the Mechanism API: the bad-input campaign of tests/test_mechanism.py"
    ),
    "mechkit/base/joint_arguments.py": (
        "the joint-naming argument checks of the Mechanism API: the bad-input campaign of tests/test_mechanism.py"
    ),
    "mechkit/base/exceptions.py": "the error classes: raised and matched by name throughout the tests",
    "mechkit/base/resources.py": (
        "where the packaged templates and URDFs are: tests/catalog/test_contract.py reads every one"
    ),
    "mechkit/base/spatial.py": "rotation and cross-product helpers of the mechanisms' kinematics, tested with them "
    "(tests/mechanisms/truss/test_geometry.py checks the paper's rotations)",
    "mechkit/bench/charts.py": "drawn by `mechkit bench` in tests/cli/test_bench.py",
    "mechkit/bench/markdown.py": "the benchmark page, written by `mechkit bench` in tests/cli/test_bench.py",
    "mechkit/bench/raw.py": (
        "the raw constraintDynamics rows, measured in tests/bench/test_run.py and tests/cli/test_bench.py"
    ),
    "mechkit/bench/results.py": (
        "the bench's rows, built and read in tests/bench/test_timing.py and tests/bench/test_run.py"
    ),
    "mechkit/bench/sampling.py": (
        "the bench's states: tests/bench/test_methods.py measures every declared method on them"
    ),
    "mechkit/bench/scale.py": "the cost-against-size fit, printed by `mechkit bench` in tests/cli/test_bench.py",
    "mechkit/export/xmltext.py": (
        "the XML text of the MJCF export: tests/export/test_mjcf.py compiles every file in MuJoCo"
    ),
    "mechkit/independent_inputs.py": (
        "the joints a motion fixes: tests/motion/test_study.py (the ten-bar's passive input) and "
        "tests/second_opinion/test_agreement.py"
    ),
    "mechkit/mechanisms/deployable_9rr12uru/actuation.py": "the composite's actuators and home: its model tests, "
    "tests/mechanisms/test_deployable_9rr12uru.py",
    "mechkit/mechanisms/deployable_9rr12uru/figures.py": (
        "drawn in tests/mechanisms/deployable_9rr12uru/test_studies.py"
    ),
    "mechkit/mechanisms/deployable_9rr12uru/params.py": (
        "bad parameters named in tests/mechanisms/test_deployable_9rr12uru.py"
    ),
    "mechkit/mechanisms/five_bar/__init__.py": "its SPEC: tests/catalog/test_contract.py; its model against the closed "
    "form: tests/test_mechanism.py",
    "mechkit/mechanisms/five_bar/closed_form.py": (
        "the bench's reference: tests/bench/test_methods.py, tests/bench/test_run.py"
    ),
    "mechkit/mechanisms/five_bar/params.py": "checked by the property campaign, tests/catalog/test_params.py",
    "mechkit/mechanisms/four_bar/__init__.py": "its SPEC: tests/catalog/test_contract.py; its model against the closed "
    "form: tests/test_mechanism.py",
    "mechkit/mechanisms/four_bar/closed_form.py": (
        "the bench's reference: tests/bench/test_methods.py, tests/bench/test_run.py"
    ),
    "mechkit/mechanisms/planar_linkage/bench.py": "the planar linkages' bench methods and references: "
    "tests/bench/test_methods.py, tests/bench/test_run.py",
    "mechkit/mechanisms/planar_linkage/lagrange.py": (
        "a bench method of the planar linkages: tests/bench/test_methods.py"
    ),
    "mechkit/mechanisms/planar_linkage/state.py": "the planar linkages' bench states: tests/bench/test_methods.py",
    "mechkit/mechanisms/rocket_gimbal/__init__.py": "its SPEC: tests/catalog/test_contract.py; its parts: "
    "tests/mechanisms/rocket_gimbal/",
    "mechkit/mechanisms/rocket_gimbal/design.py": "its metric is `kinematics.linear_rule_errors` on a grid, which "
    "tests/mechanisms/rocket_gimbal/test_studies.py runs through the "
    "linearisation study; the sweep hook itself has no test of its own",
    "mechkit/mechanisms/rocket_gimbal/figures.py": "drawn in tests/mechanisms/rocket_gimbal/test_studies.py",
    "mechkit/mechanisms/spherical_2dof/figures.py": "drawn in tests/mechanisms/spherical_2dof/test_studies.py",
    "mechkit/mechanisms/ten_bar/design.py": (
        "the deployment metric, read through the sweep: tests/sweep/test_specific.py"
    ),
    "mechkit/mechanisms/ten_bar/lagrange_deployment.py": "the Lagrange route of the deployment, against the Pinocchio "
    "route in tests/mechanisms/ten_bar/test_dynamics.py",
    "mechkit/mechanisms/ten_bar/lagrange_model.py": (
        "the patent's Lagrange model: tests/mechanisms/ten_bar/test_dynamics.py and "
        "tests/mechanisms/ten_bar/test_checks.py"
    ),
    "mechkit/mechanisms/ten_bar/scenes.py": (
        "the deployment scene: tests/mechanisms/test_ten_bar.py (the deployment law)"
    ),
    "mechkit/mechanisms/ten_bar/soc.py": "reactions three ways: tests/mechanisms/ten_bar/test_checks.py",
    "mechkit/mechanisms/tetra_3rr3uru/actuation.py": (
        "the unit's actuators and home: tests/mechanisms/test_tetra_3rr3uru.py"
    ),
    "mechkit/mechanisms/tetra_3rr3uru/checks.py": "its report rows: tests/test_report.py",
    "mechkit/mechanisms/truss/bench.py": "the fold states of the bench: tests/mechanisms/tetra_3rr3uru/test_bench.py",
    "mechkit/mechanisms/truss/checks.py": "the truss mechanisms' report rows: tests/test_report.py",
    "mechkit/mechanisms/truss/joint_state.py": (
        "the web-joint laws the fold follows: tests/mechanisms/truss/test_fold.py"
    ),
    "mechkit/mechanisms/truss/nodes.py": "node centres along the fold: tests/mechanisms/truss/test_fold.py and "
    "tests/mechanisms/test_deployable_9rr12uru.py",
    "mechkit/motion/plot.py": "drawn by `mechkit motion --plot` in tests/cli/test_motion.py",
    "mechkit/second_opinion/instant.py": "a part of every second opinion: tests/second_opinion/test_agreement.py",
    "mechkit/second_opinion/solve.py": "a part of every second opinion: tests/second_opinion/test_agreement.py",
    "mechkit/second_opinion/structure_graph.py": (
        "what the decomposition reads: tests/second_opinion/test_decomposition.py"
    ),
    "mechkit/sources/description.py": (
        "what every reader returns: tests/sources/test_mjcf.py, tests/sources/test_sdf.py"
    ),
    "mechkit/sources/mjcf/constraints.py": "a part of the MJCF reader: tests/sources/test_mjcf.py",
    "mechkit/sources/mjcf/tree.py": "a part of the MJCF reader: tests/sources/test_mjcf.py",
    "mechkit/sources/pinocchio_tree.py": "the trees of the MJCF and SDFormat readers: tests/sources/test_mjcf.py, "
    "tests/sources/test_sdf.py",
    "mechkit/sweep/store.py": "written, resumed and read in tests/sweep/test_engine.py",
    "mechkit/validation/planar_motion.py": "the planar linkages' state: tests/validation/test_planar_closed_form.py",
    "mechkit/viz/browser.py": "the screenshots of every real-browser test (tests/viz/in_browser.py)",
    "mechkit/viz/inline.py": "the inline views of the tour notebook: tests/docs/test_tour_notebook.py",
    "mechkit/viz/live.py": "the live viewer in a real browser: tests/cli/test_view.py",
    "mechkit/viz/meshcat_page.py": "the pages tests/viz/test_pages.py decodes command by command",
}


def _has_code(init: Path) -> bool:
    """Whether a package's face defines something (beyond its docstring, imports and `__all__`)."""
    for node in ast.parse(init.read_text()).body:
        if isinstance(node, (ast.Import, ast.ImportFrom)) or (
            isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant)
        ):
            continue
        if isinstance(node, ast.Assign) and all(isinstance(t, ast.Name) and t.id == "__all__" for t in node.targets):
            continue
        return True
    return False


def _mirrored_test(path: Path) -> Path | None:
    """Where the test of a module is: `tests/x/test_y.py` for `mechkit/x/y.py`, and for the face of a
    package `mechkit/x/y/__init__.py` (when it defines something) the same, `tests/x/test_y.py`; None for
    a face that only gathers names (and the package's own face)."""
    relative = path.relative_to(PACKAGE)
    if path.name != "__init__.py":
        return ROOT / "tests" / relative.parent / f"test_{path.stem}.py"
    if path.parent == PACKAGE or not _has_code(path):
        return None
    return ROOT / "tests" / relative.parent.parent / f"test_{path.parent.name}.py"


def test_every_module_has_its_test_file():
    """A reader finds the test of `mechkit/x/y.py` at `tests/x/test_y.py`; the modules tested elsewhere say
    where, and that list holds no module that has its test file or no longer exists."""
    missing, listed = [], []
    for path in sorted(PACKAGE.rglob("*.py")):
        test = _mirrored_test(path)
        name = str(path.relative_to(ROOT))
        if name in TESTED_ELSEWHERE:
            listed.append(name)
            assert test is None or not test.is_file(), (
                f"{name} has {test.relative_to(ROOT)}: drop it from TESTED_ELSEWHERE"
            )
        elif test is not None and not test.is_file():
            missing.append(f"{name} -> {test.relative_to(ROOT)}")
    assert not missing, missing
    assert sorted(TESTED_ELSEWHERE) == listed, sorted(set(TESTED_ELSEWHERE) - set(listed))


def test_the_mirror_of_a_module_and_of_a_face():
    """The rule itself: a module's test is beside its folder's mirror, a face's is named after its package."""
    assert _mirrored_test(PACKAGE / "sweep" / "engine.py") == ROOT / "tests" / "sweep" / "test_engine.py"
    assert _mirrored_test(PACKAGE / "cli" / "__init__.py") == ROOT / "tests" / "test_cli.py"
    assert (
        _mirrored_test(PACKAGE / "mechanisms" / "ten_bar" / "__init__.py")
        == ROOT / "tests" / "mechanisms" / "test_ten_bar.py"
    )
    assert (
        _mirrored_test(PACKAGE / "__init__.py") is None
        and _mirrored_test(PACKAGE / "validation" / "__init__.py") is None
    )


#: Module names found in several folders of mechkit, each one concept wherever it appears: why, and where
#: it may appear (a package is its folder, with a trailing slash). Any other repeated name fails.
SAME_CONCEPT = {
    "actuation": ("a mechanism package's actuators and home", ("mechkit/mechanisms/*/actuation.py",)),
    "bench": (
        (
            "the bench: mechkit/bench/ measures, cli/bench.py is `mechkit bench`, a mechanism package's bench.py "
            "declares the methods it adds to it"
        ),
        ("mechkit/bench/", "mechkit/cli/bench.py", "mechkit/mechanisms/*/bench.py"),
    ),
    "checks": ("a mechanism package's self-checks (the rows of `mechkit report`)", ("mechkit/mechanisms/*/checks.py",)),
    "closed_form": ("a planar calibration linkage's closed form", ("mechkit/mechanisms/*/closed_form.py",)),
    "design": (
        "a mechanism's figures of merit for a sweep (`MechanismSpec.design_metrics`)",
        ("mechkit/mechanisms/*/design.py",),
    ),
    "export": (
        "exporting a mechanism: the package, and `mechkit export` (cli/export.py)",
        ("mechkit/export/", "mechkit/cli/export.py"),
    ),
    "extended_urdf": (
        "the Extended URDF format: sources/ reads it, export/ writes it",
        ("mechkit/sources/extended_urdf.py", "mechkit/export/extended_urdf.py"),
    ),
    "failure": (
        "a mechanism's failure-atlas study (`MechanismSpec.failure_studies`)",
        ("mechkit/mechanisms/*/failure.py",),
    ),
    "figures": ("a mechanism's figures, drawn from its studies' data", ("mechkit/mechanisms/*/figures.py",)),
    "geometry": ("a mechanism package's paper geometry (numpy only)", ("mechkit/mechanisms/*/geometry.py",)),
    "joint_state": (
        "a mechanism's analytic state written on (and read from) its URDF tree's joints",
        ("mechkit/mechanisms/*/joint_state.py",),
    ),
    "kinematics": (
        (
            "a mechanism's kinematics: the core's numerical closure kinematics, and each mechanism package's "
            "from its paper"
        ),
        ("mechkit/core/kinematics.py", "mechkit/mechanisms/*/kinematics.py"),
    ),
    "lagrange": (
        ("Lagrange's equations of the first kind: the method (validation/) and the planar linkages written in it"),
        ("mechkit/validation/lagrange.py", "mechkit/mechanisms/planar_linkage/lagrange.py"),
    ),
    "mjcf": (
        "the MJCF format: sources/mjcf/ reads it, export/ writes it",
        ("mechkit/sources/mjcf/", "mechkit/export/mjcf.py"),
    ),
    "motion": (
        "motion studies: the package, and `mechkit motion` (cli/motion.py)",
        ("mechkit/motion/", "mechkit/cli/motion.py"),
    ),
    "params": (
        (
            "a mechanism's parameters: their base class (catalog/), each mechanism package's class, and `mechkit "
            "params` (cli/), which lists them"
        ),
        ("mechkit/catalog/params.py", "mechkit/cli/params.py", "mechkit/mechanisms/*/params.py"),
    ),
    "modes": (
        "natural frequencies and mode shapes: elastic/modes.py computes them, `mechkit modes` (cli/) prints them",
        ("mechkit/elastic/modes.py", "mechkit/cli/modes.py"),
    ),
    "plot": (
        "the figure of a study over time: a motion study's (motion/) and a simulation's (simulation/)",
        ("mechkit/motion/plot.py", "mechkit/simulation/plot.py"),
    ),
    "report": (
        "a mechanism's report: the library module, and `mechkit report` (cli/report.py)",
        ("mechkit/report.py", "mechkit/cli/report.py"),
    ),
    "results": (
        (
            "a package's result types, what its functions return: the core's (mobility, dynamics), the bench's "
            "(its rows)"
        ),
        ("mechkit/core/results.py", "mechkit/bench/results.py"),
    ),
    "result": (
        (
            "the arrays and table of a study over time: a motion study's (history/), and a simulation's, which "
            "extends it with time, energies and events (simulation/)"
        ),
        ("mechkit/history/result.py", "mechkit/simulation/result.py"),
    ),
    "scenes": (
        ("a mechanism's scenes: the protocol with the generic sweep (scenes.py), and each mechanism package's own"),
        ("mechkit/scenes.py", "mechkit/mechanisms/*/scenes.py"),
    ),
    "simulate": (
        "simulation in time: simulation/simulate.py runs it, `mechkit simulate` (cli/) prints and writes it",
        ("mechkit/simulation/simulate.py", "mechkit/cli/simulate.py"),
    ),
    "soc": (
        (
            "sequential SOC virtual work: the solver (validation/soc.py) and each mechanism package's hand-written "
            "decomposition solved by it"
        ),
        ("mechkit/validation/soc.py", "mechkit/mechanisms/*/soc.py"),
    ),
    "studies": ("a mechanism package's studies, returning data", ("mechkit/mechanisms/*/studies.py",)),
    "sweep": (
        "design sweeps: the package, and `mechkit sweep` (cli/sweep.py)",
        ("mechkit/sweep/", "mechkit/cli/sweep.py"),
    ),
    "urdf": (
        "URDF: sources/urdf.py reads it, export/urdf.py writes a mechanism's, cli/urdf.py is `mechkit urdf`",
        ("mechkit/sources/urdf.py", "mechkit/export/urdf.py", "mechkit/cli/urdf.py"),
    ),
    "urdf_plus": (
        "the URDF+ format: sources/ reads it, export/ writes it",
        ("mechkit/sources/urdf_plus.py", "mechkit/export/urdf_plus.py"),
    ),
}


def _repeated_names() -> dict[str, list[str]]:
    """Module names (a package by its folder's name) found in more than one folder of mechkit, and where."""
    found: dict[str, list[str]] = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        if path.name == "__main__.py" or path == PACKAGE / "__init__.py":
            continue
        if path.name == "__init__.py":
            found.setdefault(path.parent.name, []).append(f"{path.parent.relative_to(ROOT)}/")
        else:
            found.setdefault(path.stem, []).append(str(path.relative_to(ROOT)))
    return {name: where for name, where in found.items() if len(where) > 1}


def test_a_module_name_in_several_folders_is_one_concept():
    """No two modules share a name unless they are one concept (listed in `SAME_CONCEPT`, with where)."""
    repeated = _repeated_names()
    unexplained = {name: where for name, where in repeated.items() if name not in SAME_CONCEPT}
    astray = {
        name: [w for w in where if not any(fnmatch(w, p) for p in SAME_CONCEPT[name][1])]
        for name, where in repeated.items()
        if name in SAME_CONCEPT
    }
    assert not unexplained, f"rename, or add to SAME_CONCEPT with the reason: {unexplained}"
    assert not any(astray.values()), {name: where for name, where in astray.items() if where}
    assert set(SAME_CONCEPT) <= set(repeated), f"no longer repeated: {sorted(set(SAME_CONCEPT) - set(repeated))}"
