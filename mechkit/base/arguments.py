"""Checks of what a public function is given, before any numerical work: shape, dtype, finiteness, options.

Every check raises a named `MechkitError` subclass (`InvalidArgument`, `UnknownOption`) that says which
argument and why, so bad input never reaches Pinocchio or LAPACK (no C++ error, no "DLASCL" line on
stderr, no NaN result). State vectors may carry a leading sample axis: a q of shape (nq,) or (N, nq).
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import InvalidArgument, UnknownOption


def array(name: str, value: Any, size: int, *, batch: bool = True) -> np.ndarray:
    """A real, finite float array of shape (size,) or, when `batch`, (N, size).

    Args:
        name: the argument's name (for the error).
        value: an array, a list or a tuple of numbers.
        size: the length of one vector (nq, nv, ...).
        batch: accept a leading sample axis.

    Raises:
        InvalidArgument: not numbers (None, strings, complex, objects), wrong shape, NaN or inf.
    """
    if value is None or isinstance(value, (str, bytes, Mapping)):
        raise InvalidArgument(name, value, f"expected an array of {size} numbers")
    try:
        raw = np.asarray(value)
    except (ValueError, TypeError):
        raise InvalidArgument(name, value, f"expected an array of {size} numbers (ragged or not numeric)") from None
    if raw.dtype.kind not in "biuf":
        raise InvalidArgument(name, value, f"expected real numbers, got dtype {raw.dtype}")
    x = raw.astype(float)
    shapes = f"({size},)" + (f" or (N, {size})" if batch else "")
    if not (x.shape == (size,) or (batch and x.ndim == 2 and x.shape[1] == size and x.shape[0] > 0)):
        raise InvalidArgument(name, value, f"expected shape {shapes}, got {x.shape}")
    if not np.all(np.isfinite(x)):
        bad = np.argwhere(~np.isfinite(x))[0].tolist()
        raise InvalidArgument(name, value, f"must be finite (NaN or inf at index {bad})")
    return x


def state(sizes: Mapping[str, int], **values: Any) -> list[np.ndarray]:
    """Several state arrays checked by `array`, which must agree on the sample axis.

    Args:
        sizes: argument name -> vector length (e.g. {"q": nq, "v": nv}).
        values: argument name -> value, in the order returned.

    Raises:
        InvalidArgument: one array is malformed, or one is batched and another is not / has another N.
    """
    out = [array(name, value, sizes[name]) for name, value in values.items()]
    leading = {name: (x.shape[0] if x.ndim == 2 else None) for name, x in zip(values, out)}
    if len(set(leading.values())) > 1:
        raise InvalidArgument(", ".join(values), leading, "every state array must have the same leading sample axis "
                              "(all (n,) or all (N, n) with one N)")
    return out


def option(name: str, value: Any, choices: Sequence[str]) -> str:
    """An option's value, one of `choices`.

    Raises:
        UnknownOption: anything else (another string, None, a number).
    """
    if not isinstance(value, str) or value not in choices:
        raise UnknownOption(name, value, tuple(choices))
    return value


def number(name: str, value: Any, *, minimum: float | None = None, positive: bool = False) -> float:
    """A finite real number, optionally >= minimum or > 0.

    Raises:
        InvalidArgument: not a real number (bools, strings, None), not finite, or out of range.
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise InvalidArgument(name, value, "expected a real number")
    x = float(value)
    if not math.isfinite(x):
        raise InvalidArgument(name, value, "must be finite")
    if positive and x <= 0:
        raise InvalidArgument(name, value, "must be > 0")
    if minimum is not None and x < minimum:
        raise InvalidArgument(name, value, f"must be >= {minimum}")
    return x


def solver_settings(mu: Any, accuracy: Any, max_iter: Any, baumgarte: Any) -> tuple[float, float, int, tuple | None]:
    """Forward-dynamics settings checked: mu >= 0, accuracy > 0, max_iter >= 1, baumgarte None or 2 finite gains.

    Raises:
        InvalidArgument: naming the first bad one.
    """
    gains = None if baumgarte is None else tuple(array("baumgarte", baumgarte, 2, batch=False))
    return (number("mu", mu, minimum=0.0), number("accuracy", accuracy, positive=True),
            integer("max_iter", max_iter, minimum=1), gains)


def integer(name: str, value: Any, *, minimum: int = 0) -> int:
    """An integer >= minimum (bools refused).

    Raises:
        InvalidArgument: not an integer, or below the minimum.
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise InvalidArgument(name, value, "expected an integer")
    if value < minimum:
        raise InvalidArgument(name, value, f"must be >= {minimum}")
    return int(value)


def flag(name: str, value: Any) -> bool:
    """A bool (numpy bools too).

    Raises:
        InvalidArgument: anything else (a string "False" would otherwise count as True).
    """
    if not isinstance(value, (bool, np.bool_)):
        raise InvalidArgument(name, value, "expected True or False")
    return bool(value)


def joint_names(name: str, value: Any, known: Sequence[str], *, allow_empty: bool = False) -> list[str]:
    """A sequence of distinct joint names, each one of `known`.

    Raises:
        InvalidArgument: not a sequence of strings, an unknown or repeated name, or empty.
    """
    if isinstance(value, (str, bytes)) or not isinstance(value, Sequence | np.ndarray):
        raise InvalidArgument(name, value, "expected a sequence of joint names")
    names = list(value)
    for joint in names:
        if not isinstance(joint, str) or joint not in known:
            raise InvalidArgument(name, value, f"{joint!r} is not a joint; joints: {list(known)}")
    if len(set(names)) != len(names):
        raise InvalidArgument(name, value, "a joint is named twice")
    if not names and not allow_empty:
        raise InvalidArgument(name, value, "give at least one joint")
    return names


def joint_values(name: str, value: Any, names: Sequence[str], known: Sequence[str]) -> dict[str, float]:
    """Joint values as {joint: finite float}: a mapping by name, or numbers in the order of `names`.

    Raises:
        InvalidArgument: unknown joints, wrong count, non-numbers, NaN or inf.
    """
    if isinstance(value, Mapping):
        joint_names(name, list(value), known, allow_empty=True)
        return {joint: number(f"{name}[{joint!r}]", v) for joint, v in value.items()}
    values = np.atleast_1d(array(name, value, len(names), batch=False)) if len(names) else array(name, value, 0, batch=False)
    return dict(zip(names, values.tolist()))


def external_forces(name: str, value: Any, njoints: int) -> Any:
    """External forces for Pinocchio's RNEA: None, or one force per joint (universe first).

    Accepts a `pin.StdVec_Force`, a sequence of `pin.Force`, or an (njoints, 6) array [f, m] in each
    joint's local frame.

    Raises:
        InvalidArgument: wrong count, wrong type, NaN or inf.
    """
    if value is None:
        return None
    if isinstance(value, (pin.StdVec_Force, list, tuple)) and all(isinstance(f, pin.Force) for f in value):
        rows = np.array([f.vector for f in value]).reshape(-1, 6)
    else:
        rows = array(name, value, 6)
        rows = rows.reshape(-1, 6)
    if rows.shape[0] != njoints:
        raise InvalidArgument(name, value, f"expected one force per joint ({njoints}, universe first), got {rows.shape[0]}")
    if not np.all(np.isfinite(rows)):
        raise InvalidArgument(name, value, "must be finite")
    out = pin.StdVec_Force()
    for row in rows:
        out.append(pin.Force(row[:3].copy(), row[3:].copy()))
    return out
