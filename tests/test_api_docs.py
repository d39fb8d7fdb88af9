"""Every public module, class and function of mechkit has a docstring and full type annotations (ast).

Public: a module whose path has no component starting with "_" (`__init__.py` counts as its package),
its top-level classes and functions whose names do not start with "_", and the methods of those
classes whose names do not start with "_". Fully annotated: every parameter but `self`/`cls`
(including *args, **kwargs) and the return.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parent.parent / "mechkit"


def _modules() -> list[Path]:
    out = []
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        if all(p == "__init__" or p == "__main__" or not p.startswith("_") for p in parts):
            out.append(path)
    return out


def _unannotated(fn: ast.FunctionDef | ast.AsyncFunctionDef, method: bool) -> list[str]:
    a = fn.args
    params = [*a.posonlyargs, *a.args, *a.kwonlyargs]
    if method and params and params[0].arg in ("self", "cls") and not any(
            isinstance(d, ast.Name) and d.id == "staticmethod" for d in fn.decorator_list):
        params = params[1:]
    params += [p for p in (a.vararg, a.kwarg) if p is not None]
    missing = [p.arg for p in params if p.annotation is None]
    if fn.returns is None:
        missing.append("return")
    return missing


def audit() -> tuple[list[str], list[str], int]:
    """(objects without a docstring, functions not fully annotated, public objects counted)."""
    no_doc, no_ann, count = [], [], 0
    for path in _modules():
        where = path.relative_to(PACKAGE.parent).as_posix()
        tree = ast.parse(path.read_text(), filename=where)
        count += 1
        if ast.get_docstring(tree) is None:
            no_doc.append(f"{where} (module)")
        for node in tree.body:
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)) and not node.name.startswith("_"):
                count += 1
                if ast.get_docstring(node) is None:
                    no_doc.append(f"{where}:{node.lineno} {node.name}")
                if isinstance(node, ast.ClassDef):
                    for sub in node.body:
                        if isinstance(sub, (ast.FunctionDef, ast.AsyncFunctionDef)) and not sub.name.startswith("_"):
                            count += 1
                            if ast.get_docstring(sub) is None:
                                no_doc.append(f"{where}:{sub.lineno} {node.name}.{sub.name}")
                            if missing := _unannotated(sub, method=True):
                                no_ann.append(f"{where}:{sub.lineno} {node.name}.{sub.name}: {', '.join(missing)}")
                elif missing := _unannotated(node, method=False):
                    no_ann.append(f"{where}:{node.lineno} {node.name}: {', '.join(missing)}")
    return no_doc, no_ann, count


def test_every_public_object_has_a_docstring_and_annotations():
    no_doc, no_ann, count = audit()
    print(f"\n{count} public modules, classes and functions; {len(no_doc)} without a docstring, "
          f"{len(no_ann)} not fully annotated")
    assert count > 300
    assert not no_doc and not no_ann, "\n".join(["no docstring:", *no_doc, "not fully annotated:", *no_ann])


def test_the_audit_sees_what_it_claims():
    """The audit flags a missing docstring, a missing parameter annotation and a missing return."""
    tree = ast.parse("def f(x, y: int):\n    return x\n")
    fn = tree.body[0]
    assert ast.get_docstring(fn) is None
    assert _unannotated(fn, method=False) == ["x", "return"]
    method = ast.parse("class A:\n    def g(self, *a: int, **k) -> None:\n        'doc'\n").body[0].body[0]
    assert _unannotated(method, method=True) == ["k"]


@pytest.mark.parametrize("page", sorted((PACKAGE.parent / "docs" / "reference").glob("*.md")))
def test_reference_pages_name_only_real_modules(page):
    import importlib

    for line in page.read_text().splitlines():
        if line.startswith("::: "):
            importlib.import_module(line[4:].strip())


def test_every_core_module_is_in_the_reference():
    """A new top-level module must be added to docs/reference/core.md (packages render their submodules)."""
    listed = (PACKAGE.parent / "docs" / "reference" / "core.md").read_text()
    for path in sorted(PACKAGE.glob("*.py")):
        if not path.stem.startswith("_"):
            assert f"::: mechkit.{path.stem}\n" in listed, path.name
    pages = "".join(p.read_text() for p in (PACKAGE.parent / "docs" / "reference").glob("*.md"))
    for package in sorted(p.parent.name for p in PACKAGE.glob("*/__init__.py")):
        assert f"::: mechkit.{package}\n" in pages, package
