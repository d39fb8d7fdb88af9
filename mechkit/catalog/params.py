"""Parameter dataclasses: every mechanism's dimensions, masses and options, with units.

A mechanism's parameters are a frozen dataclass deriving from `MechanismParams`; each field is
declared with `param(default, unit, doc, ours=...)`. Every field is passed to the mechanism's xacro
template as a `xacro:arg` of the same name.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field, fields
from typing import Any

from mechkit.base.exceptions import InvalidParameters


def param(default: float | bool | str, unit: str, doc: str, *, ours: bool = False, positive: bool | None = None) -> Any:
    """Declare one parameter.

    Args:
        default: default value (SI units, radians).
        unit: unit string for reports ("m", "kg", "rad", "-").
        doc: one line saying what it is.
        ours: True when the value is not in the source document but chosen by us.
        positive: require a value > 0 (default: True for lengths "m" and masses/densities).

    Returns:
        The dataclass field, its unit, doc and flags in its metadata.
    """
    if positive is None:
        positive = unit in ("m", "kg", "kg/m^3", "kg/m^2", "kg m^2")
    return field(default=default, metadata={"unit": unit, "doc": doc, "ours": ours, "positive": positive})


@dataclass(frozen=True)
class MechanismParams:
    """Base of every parameter dataclass: validation and conversion to xacro arguments."""

    def __post_init__(self) -> None:
        for f in fields(self):
            value = getattr(self, f.name)
            if isinstance(value, (bool, str)):
                continue
            if not isinstance(value, (int, float)) or not math.isfinite(value):
                raise InvalidParameters(f.name, value, "must be a finite number")
            if f.metadata.get("positive") and value <= 0:
                raise InvalidParameters(f.name, value, f"must be > 0 ({f.metadata.get('unit')})")
        self.validate()

    def validate(self) -> None:
        """Check relations between parameters; override and raise `InvalidParameters`."""

    @classmethod
    def from_overrides(cls, **overrides: Any) -> MechanismParams:
        """Defaults with some fields replaced (strings, as the command line gives them, converted).

        Args:
            overrides: field name -> value.

        Returns:
            The parameters, validated.

        Raises:
            InvalidParameters: an unknown name, a value of the wrong type, or one the class refuses.
        """
        known = {f.name: f for f in fields(cls)}
        for name, value in overrides.items():
            if name not in known:
                raise InvalidParameters(name, value, f"unknown parameter; known: {', '.join(known)}")
        return cls(**{name: _coerce(known[name], value) for name, value in overrides.items()})

    def xacro_args(self) -> dict[str, str]:
        """Every field as a xacro argument string (floats with full precision)."""
        return {f.name: _format(getattr(self, f.name)) for f in fields(self)}

    def describe(self) -> list[dict[str, Any]]:
        """One row per field: name, value, unit, doc, ours."""
        return [{"name": f.name, "value": getattr(self, f.name), **f.metadata} for f in fields(self)]

    def replace(self, **changes: Any) -> MechanismParams:
        """A copy with some fields changed (validated).

        Args:
            changes: field name -> value.

        Returns:
            The new parameters.

        Raises:
            InvalidParameters: a value the class refuses.
        """
        return dataclasses.replace(self, **changes)


def _coerce(f: dataclasses.Field, value: Any) -> Any:
    """Convert a CLI string to the field's type."""
    if not isinstance(value, str):
        return value
    kind = type(f.default)
    try:
        if kind is bool:
            if value.lower() in ("1", "true", "yes"):
                return True
            if value.lower() in ("0", "false", "no"):
                return False
            raise ValueError(value)
        return kind(value)
    except ValueError:
        raise InvalidParameters(f.name, value, f"expected a {kind.__name__}") from None


def _format(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(float(value))
    return str(value)
