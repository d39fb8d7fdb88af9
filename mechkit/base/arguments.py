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

from mechkit.base.exceptions import InvalidArgument, UnknownOption

#: Largest magnitude of a physical value a description or an option may give (ours): far beyond any
#: mechanism's mass, length, stiffness or load, far inside what double precision can square and sum (1e154).
LARGEST = 1e100


def array(name: str, value: Any, size: int, *, batch: bool = True) -> np.ndarray:
    """A real, finite float array of shape (size,) or, when `batch`, (N, size).

    Args:
        name: the argument's name (for the error).
        value: an array, a list or a tuple of numbers.
        size: the length of one vector (nq, nv, ...).
        batch: accept a leading sample axis.

    Returns:
        The values as a float array of shape (size,), or (N, size) for a batch.

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


def sample(sizes: Mapping[str, int], **values: Any) -> list[np.ndarray]:
    """State arrays of one sample, each checked by `array` with shape (size,).

    Args:
        sizes: argument name -> vector length (e.g. {"q": nq, "v": nv}).
        values: argument name -> value, in the order returned.

    Returns:
        The arrays, each of shape (size,) as `sizes` gives it, in the order of `values`.

    Raises:
        InvalidArgument: a malformed array, or one with a sample axis (the `*_batch` methods take those).
    """
    out = []
    for name, value in values.items():
        if _batched(value):
            raise InvalidArgument(
                name,
                value,
                f"one sample of shape ({sizes[name]},) expected; for N samples of shape "
                f"(N, {sizes[name]}) call the method's *_batch form",
            )
        out.append(array(name, value, sizes[name], batch=False))
    return out


def samples(sizes: Mapping[str, int], **values: Any) -> list[np.ndarray]:
    """State arrays of N samples, each of shape (N, size), one N for all.

    Args:
        sizes: argument name -> vector length (e.g. {"q": nq, "v": nv}).
        values: argument name -> value, in the order returned.

    Returns:
        The arrays, each of shape (N, size), with one N.

    Raises:
        InvalidArgument: a malformed array, one without a sample axis, or two different N.
    """
    out = []
    for name, value in values.items():
        x = array(name, value, sizes[name])
        if x.ndim != 2:
            raise InvalidArgument(
                name,
                value,
                f"N samples of shape (N, {sizes[name]}) expected; for one sample call the method without _batch",
            )
        out.append(x)
    if len({x.shape[0] for x in out}) > 1:
        raise InvalidArgument(
            ", ".join(values),
            {n: x.shape for n, x in zip(values, out)},
            "every state array must have the same number of samples N",
        )
    return out


def _batched(value: Any) -> bool:
    """True for a well-formed two-dimensional array of numbers (anything else is for `array` to judge)."""
    if isinstance(value, (str, bytes, Mapping)):
        return False
    try:
        return np.ndim(value) == 2
    except ValueError:  # ragged
        return False


def plain_state(q: Any, v: Any, x: Any, nq: int, nv: int, *, finite: bool = True) -> bool:
    """True for the common call that needs no conversion: float64 arrays of shapes (nq,), (nv,), (nv,)
    (q, v and tau or a), all finite. Anything else (lists, other dtypes, batches, NaN or inf) goes
    through `sample`, which converts it or names what is wrong.

    Args:
        q: a configuration, expected (nq,).
        v: a velocity, expected (nv,).
        x: generalised efforts or accelerations, expected (nv,).
        nq: configuration size of the model.
        nv: velocity size of the model.
        finite: also test the values; False where a NaN or inf argument cannot give a result (the
            caller's computation fails on it and the caller then names it through `sample`).

    Returns:
        Whether all three are float64 arrays of those shapes (and finite, with `finite`), so no
        conversion is needed.
    """
    return (
        type(q) is np.ndarray
        and type(v) is np.ndarray
        and type(x) is np.ndarray
        and q.dtype is _FLOAT
        and v.dtype is _FLOAT
        and x.dtype is _FLOAT
        and q.shape == (nq,)
        and v.shape == (nv,)
        and x.shape == (nv,)
        and (not finite or _finite(q, v, x))
    )


#: The dtype of a plain float64 array (numpy keeps one instance of each built-in dtype).
_FLOAT = np.dtype(np.float64)


def _finite(q: np.ndarray, v: np.ndarray, x: np.ndarray) -> bool:
    """Whether every entry of three 1-D float arrays is finite: first the sum of their entries as Python
    floats (which turn any NaN or inf into a NaN or inf sum and never raise or warn), then, where
    large finite entries overflow that sum, entry by entry."""
    if math.isfinite(sum(q.tolist()) + sum(v.tolist()) + sum(x.tolist())):
        return True
    return bool(np.isfinite(q).all() and np.isfinite(v).all() and np.isfinite(x).all())


def option(name: str, value: Any, choices: Sequence[str]) -> str:
    """An option's value, one of `choices`.

    Args:
        name: the option's name (for the error).
        value: what was given.
        choices: the accepted names.

    Returns:
        `value`, once checked.

    Raises:
        UnknownOption: anything else (another string, None, a number).
    """
    if not isinstance(value, str) or value not in choices:
        raise UnknownOption(name, value, tuple(choices))
    return value


def number(name: str, value: Any, *, minimum: float | None = None, positive: bool = False) -> float:
    """A finite real number, optionally >= minimum or > 0.

    Args:
        name: the argument's name (for the error).
        value: what was given.
        minimum: smallest accepted value, if any.
        positive: refuse zero and below.

    Returns:
        The value as a float.

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


def solver_settings(mu: Any, accuracy: Any, max_iter: Any, baumgarte: Any) -> dict[str, Any]:
    """Forward-dynamics settings checked (each None: the method's default).

    Args:
        mu: proximal regularisation (>= 0), or None.
        accuracy: the proximal solver's stopping tolerance (> 0), or None.
        max_iter: the proximal solver's iteration cap (>= 1), or None.
        baumgarte: Baumgarte gains (Kp, Kd), or None.

    Returns:
        The keyword arguments of `core.forward_dynamics`: "mu", "accuracy", "max_iter", "baumgarte".

    Raises:
        InvalidArgument: naming the first bad one.
    """
    return {
        "mu": None if mu is None else number("mu", mu, minimum=0.0),
        "accuracy": None if accuracy is None else number("accuracy", accuracy, positive=True),
        "max_iter": None if max_iter is None else integer("max_iter", max_iter, minimum=1),
        "baumgarte": None if baumgarte is None else tuple(array("baumgarte", baumgarte, 2, batch=False)),
    }


def integer(name: str, value: Any, *, minimum: int = 0) -> int:
    """An integer >= minimum (bools refused).

    Args:
        name: the argument's name (for the error).
        value: what was given.
        minimum: smallest accepted value.

    Returns:
        The value as an int.

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

    Args:
        name: the argument's name (for the error).
        value: what was given.

    Returns:
        The value as a bool.

    Raises:
        InvalidArgument: anything else (a string "False" would otherwise count as True).
    """
    if not isinstance(value, (bool, np.bool_)):
        raise InvalidArgument(name, value, "expected True or False")
    return bool(value)
