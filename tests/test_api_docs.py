"""Every public module, class and function of mechkit has a docstring and full type annotations, and every
public function with parameters documents them (ast).

Public: a module whose path has no component starting with "_" (`__init__.py` counts as its package),
its top-level classes and functions whose names do not start with "_", and the methods of those
classes whose names do not start with "_". Fully annotated: every parameter but `self`/`cls`
(including *args, **kwargs) and the return.

Documented (Google style, what mkdocs renders): a public function or method with parameters (`self`
and `cls` aside) has an `Args:` section naming each parameter once and nothing else; a `Returns:` (or
`Yields:`) section when it returns something (its annotation is not `None`; a property's value is
its one line); a `Raises:` section naming every exception class its own body raises.
"""

from __future__ import annotations

import ast
import re
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
    if (
        method
        and params
        and params[0].arg in ("self", "cls")
        and not any(isinstance(d, ast.Name) and d.id == "staticmethod" for d in fn.decorator_list)
    ):
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
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)) and not node.name.startswith(
                "_"
            ):
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
    print(
        f"\n{count} public modules, classes and functions; {len(no_doc)} without a docstring, "
        f"{len(no_ann)} not fully annotated"
    )
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


SECTIONS = (
    "Args",
    "Arguments",
    "Returns",
    "Yields",
    "Raises",
    "Attributes",
    "Examples",
    "Example",
    "Note",
    "Notes",
    "Warns",
    "See Also",
    "References",
)
ENTRY = re.compile(r"^ {4}(\*{0,2}\w+)(?: \([^)]*\))?:(?: |$)")


def _sections(doc: str) -> dict[str, list[str]]:
    """Section title -> its lines (Google style: a title alone on a line at the docstring's margin)."""
    out: dict[str, list[str]] = {}
    current = None
    for line in doc.splitlines():
        title = line.rstrip().removesuffix(":")
        if line.rstrip().endswith(":") and not line.startswith(" ") and title in SECTIONS:
            current = out.setdefault(title, [])
        elif current is not None and (line.startswith(" ") or not line.strip()):
            current.append(line)
        else:
            current = None
    return out


def _raised(fn: ast.FunctionDef | ast.AsyncFunctionDef) -> set[str]:
    """Exception classes a function's own body raises by name (nested functions and classes excluded)."""
    found, todo = set(), list(fn.body)
    while todo:
        node = todo.pop()
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef, ast.Lambda)):
            continue
        if isinstance(node, ast.Raise) and node.exc is not None:
            exc = node.exc.func if isinstance(node.exc, ast.Call) else node.exc
            name = exc.attr if isinstance(exc, ast.Attribute) else getattr(exc, "id", "")
            if name[:1].isupper():
                found.add(name)
        todo.extend(ast.iter_child_nodes(node))
    return found


def _parameters(fn: ast.FunctionDef | ast.AsyncFunctionDef, method: bool) -> list[str]:
    """A function's parameters as its Args section names them (`self`/`cls` of a method aside)."""
    a = fn.args
    params = [p.arg for p in [*a.posonlyargs, *a.args, *a.kwonlyargs]]
    if (
        method
        and params
        and params[0] in ("self", "cls")
        and not any(isinstance(d, ast.Name) and d.id == "staticmethod" for d in fn.decorator_list)
    ):
        params = params[1:]
    return params + ([f"*{a.vararg.arg}"] if a.vararg else []) + ([f"**{a.kwarg.arg}"] if a.kwarg else [])


def _undocumented(fn: ast.FunctionDef | ast.AsyncFunctionDef, method: bool) -> list[str]:
    """What a function's docstring lacks: parameters missing from Args (or names there that are none),
    the Returns section, exception classes missing from Raises."""
    params = _parameters(fn, method)
    if not params:
        return []
    sections = _sections(ast.get_docstring(fn) or "")
    lacks = []
    named = [m.group(1) for line in sections.get("Args", []) if (m := ENTRY.match(line))]
    stripped = [p.lstrip("*") for p in params]
    missing = [p for p, s in zip(params, stripped) if p not in named and s not in named]
    extra = [n for n in named if n not in params and n not in stripped]
    if missing:
        lacks.append("Args: " + ", ".join(missing))
    if extra or len(named) != len(set(named)):
        lacks.append("Args names no parameter or twice: " + ", ".join(extra or named))
    returns = fn.returns
    nothing = (
        returns is None
        or (isinstance(returns, ast.Constant) and returns.value is None)
        or (isinstance(returns, ast.Name) and returns.id in ("None", "NoReturn"))
    )
    prop = any(isinstance(d, ast.Name) and d.id == "property" for d in fn.decorator_list)
    if not nothing and not prop and not ({"Returns", "Yields"} & set(sections)):
        lacks.append("Returns")
    listed = " ".join(sections.get("Raises", []))
    unlisted = sorted(e for e in _raised(fn) if not re.search(rf"\b{e}\b", listed))
    if unlisted:
        lacks.append("Raises: " + ", ".join(unlisted))
    return lacks


def docs_audit() -> tuple[list[str], int]:
    """(what public functions' docstrings lack, public functions with parameters counted)."""
    lacking, count = [], 0
    for path in _modules():
        where = path.relative_to(PACKAGE.parent).as_posix()
        tree = ast.parse(path.read_text(), filename=where)
        functions = [
            (node, False, node.name)
            for node in tree.body
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and not node.name.startswith("_")
        ]
        for cls in tree.body:
            if isinstance(cls, ast.ClassDef) and not cls.name.startswith("_"):
                functions += [
                    (sub, True, f"{cls.name}.{sub.name}")
                    for sub in cls.body
                    if isinstance(sub, (ast.FunctionDef, ast.AsyncFunctionDef)) and not sub.name.startswith("_")
                ]
        for fn, method, name in functions:
            lacks = _undocumented(fn, method)
            count += bool(_parameters(fn, method))
            if lacks:
                lacking.append(f"{where}:{fn.lineno} {name}: {'; '.join(lacks)}")
    return lacking, count


def test_every_public_function_documents_its_parameters_returns_and_raises():
    lacking, count = docs_audit()
    print(f"\n{count} public functions and methods with parameters; {len(lacking)} lacking a section")
    assert not lacking, "\n".join(lacking)


def test_the_docs_audit_sees_what_it_claims():
    """The audit flags a parameter missing from Args, a name there that is no parameter, a missing
    Returns and an exception raised but not listed; a complete docstring passes."""
    code = (
        '''def f(x: int, y: int) -> int:\n    """Sum.\n\n    Args:\n        x: one.\n        z: none.\n    """\n'''
        """    if x < 0:\n        raise ValueError(x)\n    return x + y\n"""
    )
    fn = ast.parse(code).body[0]
    assert _undocumented(fn, method=False) == [
        "Args: y",
        "Args names no parameter or twice: z",
        "Returns",
        "Raises: ValueError",
    ]
    good = (
        '''def f(x: int, *rest: int) -> int:\n    """Sum.\n\n    Args:\n        x (int): one.\n'''
        """        *rest: the others,\n            continued.\n\n    Returns:\n        The sum.\n\n"""
        '''    Raises:\n        ValueError: x < 0.\n    """\n    if x < 0:\n        raise ValueError(x)\n'''
        """    return x + sum(rest)\n"""
    )
    assert _undocumented(ast.parse(good).body[0], method=False) == []
    method = ast.parse("class A:\n    @property\n    def p(self) -> int:\n        'The p.'\n").body[0].body[0]
    assert _undocumented(method, method=True) == []
