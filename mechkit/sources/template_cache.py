"""The fast load path of a sweep: expand a xacro template once per structure, then substitute parameters.

xacro spends most of a load expanding macros and evaluating `${...}` expressions. `TemplateCache`
runs xacro ONCE per structure (the values of the non-float arguments: row sets, flags, integers)
with every float argument replaced by a tracer: a float that records the arithmetic done on it
(+ - * / ** and the math functions of xacro's namespace). The URDF text that run produces holds a
token wherever a traced value was written, and the recorded operations form a small program. For
new parameters the program is replayed (the same float operations in the same order, so the same
bits) and the tokens replaced: the text is EXACTLY what xacro renders.

What a tracer cannot follow (a comparison or truth test of a parameter, `int()`/`round()` of one, a
non-float result) marks the structure untraceable; so does any difference between the replayed and
xacro's own text at perturbed parameters, checked once per structure. An untraceable structure is
rendered by xacro every time (exact, not faster).
"""

from __future__ import annotations

import math
import operator
import re
from collections.abc import Callable
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from mechkit.sources.xacro_file import document_text, render_urdf

_TOKEN = re.compile(r"MkTrc(\d+)Z")
_BINARY = {
    "add": operator.add,
    "sub": operator.sub,
    "mul": operator.mul,
    "truediv": operator.truediv,
    "floordiv": operator.floordiv,
    "mod": operator.mod,
    "pow": operator.pow,
}
_PERTURB = 1e-3  # relative change of every float argument in the structure's self-check (ours)


class Untraceable(Exception):
    """The template uses a parameter in a way a tracer cannot replay."""


class _Trace:
    """The recorded program: node k is (function, arguments) with `_Ref` for earlier nodes' values."""

    def __init__(self) -> None:
        self.nodes: list[tuple[Callable[..., Any], tuple[Any, ...]]] = []
        self.leaves: dict[int, str] = {}  # node -> argument name
        self.texts: dict[int, _Sym] = {}  # text token -> the value whose str() it is

    def leaf(self, name: str, value: float) -> _Sym:
        sym = self.add(float, (value,), value)
        self.leaves[sym.node] = name
        return sym

    def add(self, fn: Callable[..., Any], args: tuple[Any, ...], value: Any) -> _Sym:
        if not isinstance(value, float):
            raise Untraceable(f"{getattr(fn, '__name__', fn)} of a parameter gave a {type(value).__name__}")
        self.nodes.append((fn, args))
        return _Sym(value, self, len(self.nodes) - 1)

    def text(self, sym: _Sym) -> str:
        token = len(self.nodes) + len(self.texts)  # unique among leaves and texts
        self.texts[token] = sym
        return f"MkTrc{token}Z"

    def replay(self, args: dict[str, str]) -> list[Any]:
        values: list[Any] = []
        for k, (fn, operands) in enumerate(self.nodes):
            if k in self.leaves:
                values.append(float(args[self.leaves[k]]))
            else:
                values.append(fn(*(values[a.node] if isinstance(a, _Ref) else a for a in operands)))
        return values


class _Ref:
    __slots__ = ("node",)

    def __init__(self, node: int):
        self.node = node


class _Sym(float):
    """A float parameter (or a value computed from parameters) whose operations are recorded."""

    def __new__(cls, value: float, trace: _Trace, node: int):
        obj = super().__new__(cls, value)
        obj.trace, obj.node = trace, node
        return obj

    def __str__(self) -> str:
        return self.trace.text(self)

    __repr__ = __str__

    def __format__(self, spec: str) -> str:
        if spec:
            raise Untraceable(f"a parameter formatted with {spec!r}")
        return str(self)

    def __bool__(self) -> bool:
        raise Untraceable("a truth test of a parameter")

    def __int__(self) -> int:
        raise Untraceable("int() of a parameter")

    def __round__(self, *_: Any) -> Any:
        raise Untraceable("round() of a parameter")

    def _compare(self, *_: Any) -> bool:
        raise Untraceable("a comparison of a parameter")

    __lt__ = __le__ = __gt__ = __ge__ = __eq__ = __ne__ = _compare
    __hash__ = None  # type: ignore[assignment]

    def __neg__(self) -> _Sym:
        return self.trace.add(operator.neg, (_Ref(self.node),), -float(self))

    def __pos__(self) -> _Sym:
        return self

    def __abs__(self) -> _Sym:
        return self.trace.add(abs, (_Ref(self.node),), abs(float(self)))


def _operand(x: Any) -> Any:
    return _Ref(x.node) if isinstance(x, _Sym) else x


def _plain(x: Any) -> Any:
    return float(x) if isinstance(x, _Sym) else x


def _traced(fn: Callable[..., Any]) -> Callable[..., Any]:
    def call(*args: Any) -> Any:
        syms = [a for a in args if isinstance(a, _Sym)]
        if not syms:
            return fn(*args)
        return syms[0].trace.add(fn, tuple(map(_operand, args)), fn(*map(_plain, args)))

    return call


def _binary(name: str, reflected: bool) -> Callable[[_Sym, Any], Any]:
    op = _BINARY[name]

    def method(self: _Sym, other: Any) -> Any:
        if not isinstance(other, (int, float)) or isinstance(other, bool):
            return NotImplemented
        a, b = (other, self) if reflected else (self, other)
        return self.trace.add(op, (_operand(a), _operand(b)), op(_plain(a), _plain(b)))

    return method


for _name in _BINARY:
    setattr(_Sym, f"__{_name}__", _binary(_name, False))
    setattr(_Sym, f"__r{_name}__", _binary(_name, True))


def _refuse(what: str) -> Callable[..., Any]:
    def fn(*args: Any) -> Any:
        raise Untraceable(f"{what}() in the template")

    return fn


@contextmanager
def _tracing(trace: _Trace, leaves: dict[str, _Sym]):
    """Patch xacro's global symbols and literal parsing for one traced run; restore them after."""
    import xacro

    table = xacro._global_symbols
    saved = dict(table)
    math_ns = table.get("math")
    saved_math = dict(math_ns) if math_ns is not None else None
    saved_literal = xacro.Table._eval_literal
    math_fns = {k: _traced(v) for k, v in vars(math).items() if callable(v) and not k.startswith("_")}
    table.update(math_fns)
    if math_ns is not None:
        math_ns.update(math_fns)
    table.update(
        {
            "float": lambda x=0.0: x if isinstance(x, _Sym) else float(x),
            "str": lambda x="": str(x),
            "abs": _traced(abs),
            "int": lambda x=0: _refuse("int")() if isinstance(x, _Sym) else int(x),
            "round": lambda x, *n: _refuse("round")() if isinstance(x, _Sym) else round(x, *n),
        }
    )
    table.update({f"MkTrc{s.node}Z": s for s in leaves.values()})
    by_token = {f"MkTrc{s.node}Z": s for s in leaves.values()}

    def literal(value: Any) -> Any:
        if isinstance(value, str):
            match = _TOKEN.fullmatch(value)
            if match and value in by_token:
                return by_token[value]
            if match and int(match.group(1)) in trace.texts:  # xacro would read float(str(x)) == x back
                return trace.texts[int(match.group(1))]
        return saved_literal(value)

    xacro.Table._eval_literal = staticmethod(literal)
    try:
        yield
    finally:
        xacro.Table._eval_literal = staticmethod(saved_literal)
        table.clear()
        table.update(saved)
        if math_ns is not None:
            math_ns.clear()
            math_ns.update(saved_math)


class _Structure:
    """One structure's URDF text with tokens, and the trace that fills them."""

    def __init__(self, path: Path, args: dict[str, str], floats: tuple[str, ...]):
        import xacro

        trace = _Trace()
        leaves = {name: trace.leaf(name, float(args[name])) for name in floats}
        mappings = {**args, **{name: f"MkTrc{s.node}Z" for name, s in leaves.items()}}
        with _tracing(trace, leaves):
            text = document_text(xacro.process_file(str(path), mappings=mappings))
        self.text, self.trace = text, trace

    def render(self, args: dict[str, str]) -> str:
        values = self.trace.replay(args)
        leaves = self.trace.leaves

        def fill(match: re.Match) -> str:
            k = int(match.group(1))
            if k in self.trace.texts:
                return str(values[self.trace.texts[k].node])
            return args[leaves[k]]  # $(arg name) outside an expression: xacro's text substitution

        return _TOKEN.sub(fill, self.text)


def _float_args(args: dict[str, str]) -> tuple[str, ...]:
    def is_float(text: str) -> bool:
        try:
            float(text)
        except ValueError:
            return False
        return not text.lstrip("+-").isdigit() and text.lower() not in ("nan", "inf", "-inf", "+inf")

    return tuple(name for name, text in args.items() if is_float(text))


class TemplateCache:
    """Renders one xacro template for many parameter sets: xacro once per structure, then substitution.

    Args:
        path: the template file.

    `render(args)` returns exactly `mechkit.sources.urdf.render_urdf(path, args)`. A cache lives as long
    as its owner keeps it (a sweep keeps one per chunk of designs): there is no module-level state.
    """

    def __init__(self, path: Path):
        self.path = Path(path)
        self._structures: dict[tuple, _Structure | None] = {}

    def structure_key(self, args: dict[str, str]) -> tuple:
        """The non-float arguments (and which arguments are floats): designs sharing it share a template.

        Args:
            args: xacro arguments (name -> text).

        Returns:
            (the names of the float arguments, the other arguments as sorted (name, text) pairs).
        """
        floats = _float_args(args)
        return floats, tuple(sorted((k, v) for k, v in args.items() if k not in floats))

    def traceable(self, args: dict[str, str]) -> bool:
        """Whether the structure of `args` renders by substitution (else through xacro each time).

        Args:
            args: xacro arguments (name -> text).

        Returns:
            Whether it does.
        """
        return self._structure(args) is not None

    def _structure(self, args: dict[str, str]) -> _Structure | None:
        key = self.structure_key(args)
        if key not in self._structures:
            self._structures[key] = self._build(args, key[0])
        return self._structures[key]

    def _build(self, args: dict[str, str], floats: tuple[str, ...]) -> _Structure | None:
        try:
            structure = _Structure(self.path, args, floats)
            for scale in (0.0, _PERTURB):  # the traced text must be xacro's, at these and other values
                probe = {
                    k: (repr(float(v) * (1 + scale * (1 + i / len(args))) + scale * 1e-3) if k in floats else v)
                    for i, (k, v) in enumerate(args.items())
                }
                if structure.render(probe) != render_urdf(self.path, probe):
                    return None
        except Exception:  # noqa: BLE001 - untraceable or failing: xacro renders (and reports) it each time
            return None
        return structure

    def render(self, args: dict[str, str]) -> str:
        """The URDF text xacro renders from the template with these arguments.

        Args:
            args: xacro arguments (name -> text).

        Returns:
            The URDF text.

        Raises:
            MalformedDescription: xacro cannot render the template at these arguments.
        """
        structure = self._structure(args)
        if structure is not None:
            try:
                return structure.render(args)
            except (ArithmeticError, ValueError):  # xacro fails there too: let it say how
                pass
        return render_urdf(self.path, args)
