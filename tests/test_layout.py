"""The package's shape: imports go down (no circle, the core never imports what sits on it), modules stay
small, the registry is lazy and explicit, and every registered mechanism fulfils the contract."""

from __future__ import annotations

import ast
import json
import subprocess
import sys
from pathlib import Path

import pytest

import mechkit
from mechkit.base.resources import urdf_dir, xacro_dir
from mechkit.catalog.contract import BENCH_QUANTITIES, MechanismSpec
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


def test_core_imports_nothing_above_it():
    """The base imports only the base; the core only the base and itself (both derived from the folders)."""
    upward = []
    for path, targets in _graph().items():
        here = _module_name(path)
        if not here.startswith(BELOW):
            continue
        allowed = ("mechkit.base",) if here.startswith("mechkit.base") else BELOW
        upward += [f"{here} -> {_module_name(t)}" for t in targets if not _module_name(t).startswith(allowed)]
    assert not upward, upward


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
        names = [a.name for a in node.names] if isinstance(node, ast.Import) else \
            [node.module or ""] if isinstance(node, ast.ImportFrom) and not node.level else []
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
    code = ("import mechkit.mechanisms.ten_bar.dynamics as td\n"
            "from mechkit.mechanisms.rocket_gimbal import resultant\n"
            "def f():\n    from mechkit.mechanisms.parallel_2t1r.motion_law import motion_law\n"
            "from mechkit.catalog.registry import get_spec\n")
    (tmp_path / "m.py").write_text(code)
    assert _mechanism_imports(tmp_path / "m.py") == ["mechkit.mechanisms.ten_bar.dynamics",
                                                     "mechkit.mechanisms.rocket_gimbal",
                                                     "mechkit.mechanisms.parallel_2t1r.motion_law"]


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
                found += [f"{path.relative_to(ROOT)}:{node.lineno} import {n}" for n in names
                          if n.split(".")[0] == "tools" or n in ("runpy",)]
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
    for kind, found in (("xacro/<name>.urdf.xacro", templates), ("urdf/<name>.urdf", urdfs),
                        ("docs/mechanisms/<name>.md", pages)):
        assert found == registered, f"{kind}: missing {sorted(registered - found)}, orphaned {sorted(found - registered)}"
    texts = "".join(p.read_text() for p in (ROOT / "xacro").glob("*.xacro"))
    macros = [p.name for p in (ROOT / "xacro").glob("*.xacro") if not p.name.endswith(".urdf.xacro")]
    assert all(f"/{m}" in texts or f"'{m}'" in texts or f'"{m}"' in texts for m in macros), macros


def test_a_circle_is_detected():
    """The detector itself: a two-file circle and a self-consistent chain."""
    a, b, c = Path("a"), Path("b"), Path("c")
    assert _strongly_connected({a: {b}, b: {a}, c: {a}}) == [[b, a]]
    assert _strongly_connected({a: {b}, b: {c}, c: set()}) == []


def test_no_module_over_the_line_limit():
    long = {str(p.relative_to(PACKAGE.parent)): n for p in PACKAGE.rglob("*.py")
            if (n := len(p.read_text().splitlines())) > MAX_LINES}
    assert not long, f"modules over {MAX_LINES} lines: {long}"


def _modules_after(code: str) -> list[str]:
    out = subprocess.run([sys.executable, "-c", code + "\nimport sys, json\n"
                          "print(json.dumps(sorted(m for m in sys.modules if m.startswith('mechkit.mechanisms'))))"],
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout.splitlines()[-1])


def test_listing_imports_no_mechanism():
    assert _modules_after("from mechkit.cli import main; main(['list'])") == []


def test_loading_one_mechanism_imports_no_other():
    """Shared packages (the planar-linkage references, the truss) may come along; other mechanisms may not."""
    loaded = _modules_after("import mechkit; mechkit.load('four_bar')")
    assert "mechkit.mechanisms.four_bar" in loaded
    others = [e.package for e in ENTRIES if e.name != "four_bar"]
    assert not [m for m in loaded if any(m == o or m.startswith(o + ".") for o in others)], loaded


def test_registry_table_is_sorted_and_unique():
    assert list(names()) == sorted(set(names()))


def test_every_mechanism_package_is_registered():
    packages = {p.parent.name for p in (PACKAGE / "mechanisms").glob("*/__init__.py")}
    declaring = {name for name in packages if "SPEC = MechanismSpec(" in (PACKAGE / "mechanisms" / name / "__init__.py").read_text()}
    assert declaring == set(names())


@pytest.mark.parametrize("entry", ENTRIES, ids=lambda e: e.name)
def test_contract(entry):
    spec = get_spec(entry.name)
    assert isinstance(spec, MechanismSpec) and spec.name == entry.name
    assert spec.summary == entry.summary
    assert spec.template_path.is_file() and spec.template_path.parent == xacro_dir()
    assert (urdf_dir() / f"{entry.name}.urdf").is_file()
    params = spec.params()
    assert spec.actuated_joints(params) and spec.gruebler_dof >= 1
    assert isinstance(spec.home(params), dict)
    assert spec.guess is None or isinstance(spec.guess(params), dict)
    assert all(callable(f) for f in spec.scenes.values())
    assert spec.view is None or len(spec.view) == 3
    assert spec.bench_methods, f"{entry.name} declares no bench method of its own"
    assert all(m.quantity in BENCH_QUANTITIES and callable(m.fn) and m.label for m in spec.bench_methods)
    assert all(r.quantity in BENCH_QUANTITIES and callable(r.fn) and r.label for r in spec.bench_references)
    assert spec.self_checks is None or callable(spec.self_checks)
    assert spec.bench_states is None or callable(spec.bench_states)
    assert all(callable(s.run) and s.name and s.condition and s.error for s in spec.failure_studies)
    assert all(callable(law.sample) and all(isinstance(j, str) for j in law.reactions) for law in spec.motion_laws.values())
    assert all(callable(m.fn) and m.columns and m.unit and m.doc for m in spec.design_metrics)
    assert all(s.doc and callable(s.run) and callable(s.lines) and (s.figures is None or callable(s.figures))
               for s in spec.studies.values())


def test_the_contract_refuses_hooks_it_cannot_use():
    """A spec names its hooks once, and captions or times only the scenes it declares."""
    from mechkit.base.exceptions import InvalidParameters
    from mechkit.catalog.contract import DesignMetric, FailureStudy
    from mechkit.catalog.params import MechanismParams

    base = {"name": "m", "params": MechanismParams, "template": "m.urdf.xacro", "actuated": ("a",), "gruebler_dof": 1,
            "home": lambda p: {"a": 0.0}}
    study = FailureStudy("s", lambda m, quick: [], "condition (-)", "error (-)")
    metric = DesignMetric("d", "-", "a metric", ("d",), lambda m: {"d": 0.0})
    for bad in ({"failure_studies": (study, study)}, {"design_metrics": (metric, metric)},
                {"scene_captions": {"nowhere": "a scene not declared"}}):
        with pytest.raises(InvalidParameters):
            MechanismSpec(**base, **bad)


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
        inside += [f"{_module_name(path)} -> {_module_name(t)}" for t in targets
                   if _module_name(t).startswith("mechkit.core.") and t != face]
    assert not inside, inside


#: Pinocchio's constraint API (legacy and newer): only `mechkit/core/pin_constraints.py` names it.
CONSTRAINT_API = {
    "RigidConstraintModel", "RigidConstraintData", "StdVec_RigidConstraintModel", "StdVec_RigidConstraintData",
    "ProximalSettings", "constraintDynamics", "initConstraintDynamics", "lcaba", "computeJointMinimalOrdering",
    "getConstraintsJacobian", "BaumgarteCorrectorParameters", "ContactType", "PointAnchorConstraintModel",
    "FrameAnchorConstraintModel", "ConstraintModel", "ConstraintData", "ConstraintCholeskyDecomposition",
    "ContactCholeskyDecomposition", "ADMMConstraintSolver", "PGSConstraintSolver", "contactInverseDynamics",
    "convertToRigidConstraintModel", "buildModelAndConstraintsFromMJCF", "buildModelAndLegacyConstraintsFromMJCF",
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


def test_every_core_module_has_its_test_file():
    """The test of `mechkit/core/<module>.py` is `tests/core/test_<module>.py`."""
    tests = PACKAGE.parent / "tests" / "core"
    missing = [p.name for p in sorted((PACKAGE / "core").glob("*.py"))
               if p.name != "__init__.py" and not (tests / f"test_{p.stem}.py").is_file()]
    assert not missing, missing
