"""The valid range of each parameter of a mechanism, measured from its parameter class's own validation.

A parameter class states its limits in code (`positive` fields, `MechanismParams.validate`); this
module reads them back by bisection: holding every other field at its default, it moves one numeric
field away from its default until the class raises `InvalidParameters`, then bisects the boundary
to `REL_TOL`. A bound farther than `SEARCH_SPAN` times the scale from the default is reported as
open. The result is what the class accepts, not what the assembly can reach: a value inside the
range may still fail to assemble at the home inputs.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

from mechkit.base.exceptions import InvalidParameters
from mechkit.catalog.params import MechanismParams

#: Relative width (of the search scale) to which a boundary is bisected.
REL_TOL = 1e-6
#: The search stops this many scales away from the default (the bound is then open).
SEARCH_SPAN = 2.0**20
#: A boundary within `REL_TOL` of a value of this many significant digits is that value.
ROUND_DIGITS = 4
#: Step of the outward search at least this (the parameter's unit), for defaults at zero.
MIN_SCALE = 1e-3


@dataclass(frozen=True)
class ParamRange:
    """The values of one parameter the class accepts, others at their defaults.

    Attributes:
        name: the field's name.
        lower, upper: the boundaries (the field's unit); None when open.
        lower_closed, upper_closed: whether the boundary value itself is accepted.
    """

    name: str
    lower: float | None
    upper: float | None
    lower_closed: bool = False
    upper_closed: bool = False

    def text(self) -> str:
        """The range as interval text, e.g. "(0, 0.6463)", "> 0", "any"."""
        if self.lower is None and self.upper is None:
            return "any"
        if self.upper is None:
            return f"{'>=' if self.lower_closed else '>'} {self.lower:.6g}"
        if self.lower is None:
            return f"{'<=' if self.upper_closed else '<'} {self.upper:.6g}"
        return (
            f"{'[' if self.lower_closed else '('}{self.lower:.6g}, {self.upper:.6g}{']' if self.upper_closed else ')'}"
        )


def _accepts(cls: type[MechanismParams], name: str, value: float) -> bool:
    try:
        cls(**{name: value})
    except InvalidParameters:
        return False
    return True


def _boundary(
    cls: type[MechanismParams], name: str, default: float, direction: int, kind: type
) -> tuple[float | None, bool]:
    """Boundary of the accepted values from `default` along `direction` (+1 / -1) and whether it is accepted."""
    scale = max(abs(default), MIN_SCALE)
    inside, step = default, scale
    while step <= SEARCH_SPAN * scale:
        trial = default + direction * step
        if kind is int:
            trial = round(trial)
        if not _accepts(cls, name, trial):
            break
        inside, step = trial, 2 * step
    else:
        return None, False
    outside = trial
    if kind is int:
        while abs(outside - inside) > 1:
            mid = (inside + outside) // 2 if direction > 0 else -((-inside - outside) // 2)
            inside, outside = (mid, outside) if _accepts(cls, name, mid) else (inside, mid)
        return float(inside), True
    while abs(outside - inside) > REL_TOL * scale:
        mid = 0.5 * (inside + outside)
        inside, outside = (mid, outside) if _accepts(cls, name, mid) else (inside, mid)
    # a boundary at a round value (0 of a positive field, a length sum) is reported exactly, with
    # whether the value itself is accepted; any other is the bisected point, reported open
    exact = 0.0 if abs(outside) <= REL_TOL * scale else float(f"{outside:.{ROUND_DIGITS}g}")
    if abs(exact - outside) <= REL_TOL * scale:
        return exact + 0.0, _accepts(cls, name, exact)
    return 0.5 * (inside + outside), False


def param_ranges(cls: type[MechanismParams]) -> dict[str, ParamRange | None]:
    """Accepted range of every numeric field of a parameter class (None for booleans and strings).

    Args:
        cls: a parameter class.

    Returns:
        Field name -> its range (bisected from the class's own checks), None for booleans and strings.
    """
    defaults = cls()
    out: dict[str, ParamRange | None] = {}
    for f in fields(cls):
        value = getattr(defaults, f.name)
        if isinstance(value, (bool, str)) or not isinstance(value, (int, float)):
            out[f.name] = None
            continue
        kind = int if isinstance(value, int) else float
        lower, lower_closed = _boundary(cls, f.name, float(value), -1, kind)
        upper, upper_closed = _boundary(cls, f.name, float(value), +1, kind)
        out[f.name] = ParamRange(f.name, lower, upper, lower_closed, upper_closed)
    return out
