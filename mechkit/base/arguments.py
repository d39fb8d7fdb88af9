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


def sample(sizes: Mapping[str, int], **values: Any) -> list[np.ndarray]:
    """State arrays of one sample, each checked by `array` with shape (size,).

    Args:
        sizes: argument name -> vector length (e.g. {"q": nq, "v": nv}).
        values: argument name -> value, in the order returned.

    Raises:
        InvalidArgument: a malformed array, or one with a sample axis (the `*_batch` methods take those).
    """
    out = []
    for name, value in values.items():
        if _batched(value):
            raise InvalidArgument(name, value, f"one sample of shape ({sizes[name]},) expected; for N samples of shape "
                                  f"(N, {sizes[name]}) call the method's *_batch form")
        out.append(array(name, value, sizes[name], batch=False))
    return out


def samples(sizes: Mapping[str, int], **values: Any) -> list[np.ndarray]:
    """State arrays of N samples, each of shape (N, size), one N for all.

    Raises:
        InvalidArgument: a malformed array, one without a sample axis, or two different N.
    """
    out = []
    for name, value in values.items():
        x = array(name, value, sizes[name])
        if x.ndim != 2:
            raise InvalidArgument(name, value, f"N samples of shape (N, {sizes[name]}) expected; for one sample call "
                                  "the method without _batch")
        out.append(x)
    if len({x.shape[0] for x in out}) > 1:
        raise InvalidArgument(", ".join(values), {n: x.shape for n, x in zip(values, out)},
                              "every state array must have the same number of samples N")
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
        finite: also test the values; False where a NaN or inf argument cannot give a result (the
            caller's computation fails on it and the caller then names it through `sample`).
    """
    return (type(q) is np.ndarray and type(v) is np.ndarray and type(x) is np.ndarray
            and q.dtype is _FLOAT and v.dtype is _FLOAT and x.dtype is _FLOAT
            and q.shape == (nq,) and v.shape == (nv,) and x.shape == (nv,) and (not finite or _finite(q, v, x)))


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


def solver_settings(mu: Any, accuracy: Any, max_iter: Any, baumgarte: Any) -> dict[str, Any]:
    """Forward-dynamics settings checked: mu >= 0, accuracy > 0, max_iter >= 1 (each None: the method's
    default), baumgarte None or 2 finite gains; as keyword arguments of `core.forward_dynamics`.

    Raises:
        InvalidArgument: naming the first bad one.
    """
    return {"mu": None if mu is None else number("mu", mu, minimum=0.0),
            "accuracy": None if accuracy is None else number("accuracy", accuracy, positive=True),
            "max_iter": None if max_iter is None else integer("max_iter", max_iter, minimum=1),
            "baumgarte": None if baumgarte is None else tuple(array("baumgarte", baumgarte, 2, batch=False))}


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


def joint_values(name: str, value: Any, names: Sequence[str], known: Sequence[str],
                 sizes: Mapping[str, int] | None = None) -> dict[str, float | np.ndarray]:
    """Joint values as {joint: finite float, or array for a joint of several freedoms}: a mapping by
    name, or numbers in the order of `names` (each joint taking `sizes[joint]` of them, default 1).

    Raises:
        InvalidArgument: unknown joints, wrong count, non-numbers, NaN or inf.
    """
    if isinstance(value, Mapping):
        joint_names(name, list(value), known, allow_empty=True)
        out = {}
        for joint, v in value.items():
            if np.ndim(v) == 0:
                out[joint] = number(f"{name}[{joint!r}]", v)
            else:
                out[joint] = array(f"{name}[{joint!r}]", v, int(np.size(v)), batch=False)
        return out
    widths = [1 if sizes is None else sizes.get(n, 1) for n in names]
    flat = array(name, value, sum(widths), batch=False) if widths else array(name, value, 0, batch=False)
    out, i = {}, 0
    for joint, w in zip(names, widths):
        out[joint] = float(flat[i]) if w == 1 else flat[i:i + w].copy()
        i += w
    return out


def sample_inputs(name: str, values: Any, names: Sequence[str], n: int, known: Sequence[str],
                  sizes: Mapping[str, int] | None = None) -> tuple[list[str], np.ndarray]:
    """Batched input values: an (n, k) array in `names` order (k the sum of their `sizes`, default 1
    each), or a mapping joint name -> (n,) values (or (n, size) for a joint of several freedoms).

    Returns:
        The joint names and an (n, k) float array.

    Raises:
        InvalidArgument: unknown joints, wrong shape, non-numbers, NaN or inf.
    """
    width = {j: 1 if sizes is None else sizes.get(j, 1) for j in known}
    if isinstance(values, Mapping):
        keys = joint_names(name, list(values), known, allow_empty=True)
        cols = []
        for k in keys:
            v = values[k]
            if np.ndim(v) == 0 and width[k] == 1:
                cols.append(np.full((n, 1), number(f"{name}[{k!r}]", v)))
            else:
                cols.append(array(f"{name}[{k!r}]", np.reshape(v, (n, width[k])) if np.size(v) == n * width[k] else v,
                                  width[k]).reshape(n, width[k]))
        return keys, (np.concatenate(cols, axis=1) if cols else np.zeros((n, 0)))
    k = sum(width[j] for j in names)
    x = array(name, values, k)
    if x.shape != (n, k):
        raise InvalidArgument(name, values, f"expected shape ({n}, {k}): one row per sample")
    return list(names), x


def sample_fext(name: str, fext: Any, n: int, njoints: int) -> list:
    """Per-sample external forces: None, an (n, njoints, 6) array of local-frame wrenches, or n per-sample
    values (each as `external_forces` takes).

    Raises:
        InvalidArgument: a wrong shape or count.
    """
    if fext is None:
        return [None] * n
    if isinstance(fext, np.ndarray):
        if fext.shape != (n, njoints, 6):
            raise InvalidArgument(name, fext, f"expected ({n}, {njoints}, 6) or {n} per-sample values")
        return [external_forces(name, sample, njoints) for sample in fext]
    if len(fext) != n:
        raise InvalidArgument(name, fext, f"expected one value per sample ({n})")
    return [external_forces(name, f, njoints) for f in fext]


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
