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
            raise InvalidArgument(name, value, f"one sample of shape ({sizes[name]},) expected; for N samples of shape "
                                  f"(N, {sizes[name]}) call the method's *_batch form")
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


def plain_state(q: Any, v: Any, tau: Any, nq: int, nv: int) -> bool:
    """True for the common call that needs no conversion: float64 arrays of shapes (nq,), (nv,), (nv,),
    all finite. Anything else (lists, other dtypes, batches, NaN or inf) goes through `sample`, which
    converts it or names what is wrong.

    Args:
        q: a configuration, expected (nq,).
        v: a velocity, expected (nv,).
        tau: generalised efforts, expected (nv,).
        nq: configuration size of the model.
        nv: velocity size of the model.

    Returns:
        Whether all three are finite float64 arrays of those shapes (so no conversion is needed).
    """
    return (isinstance(q, np.ndarray) and isinstance(v, np.ndarray) and isinstance(tau, np.ndarray)
            and q.dtype == np.float64 and v.dtype == np.float64 and tau.dtype == np.float64
            and q.shape == (nq,) and v.shape == (nv,) and tau.shape == (nv,)
            and bool(np.isfinite(q).all() and np.isfinite(v).all() and np.isfinite(tau).all()))


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
    return {"mu": None if mu is None else number("mu", mu, minimum=0.0),
            "accuracy": None if accuracy is None else number("accuracy", accuracy, positive=True),
            "max_iter": None if max_iter is None else integer("max_iter", max_iter, minimum=1),
            "baumgarte": None if baumgarte is None else tuple(array("baumgarte", baumgarte, 2, batch=False))}


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


def joint_names(name: str, value: Any, known: Sequence[str], *, allow_empty: bool = False) -> list[str]:
    """A sequence of distinct joint names, each one of `known`.

    Args:
        name: the argument's name (for the error).
        value: a sequence of joint names.
        known: the model's joint names.
        allow_empty: accept an empty sequence.

    Returns:
        The names, in the order given.

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

    Args:
        name: the argument's name (for the error).
        value: a mapping joint -> value, or numbers in the order of `names`.
        names: the joints a sequence of numbers is read for, in order.
        known: the model's joint names (the keys a mapping may use).
        sizes: joint -> how many numbers it takes (its freedoms; default 1).

    Returns:
        Joint -> value: a float (rad or m) for a joint of one freedom, a float array of its size otherwise.

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

    Args:
        name: the argument's name (for the error).
        values: an (n, k) array in `names` order, or a mapping joint -> (n,) or (n, size) values (a scalar: the
            same for every sample).
        names: the joints, in the order of an array's columns.
        n: number of samples.
        known: the model's joint names (the keys a mapping may use).
        sizes: joint -> how many columns it takes (its freedoms; default 1).

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
    """Per-sample external forces.

    Args:
        name: the argument's name (for the error).
        fext: None, an (n, njoints, 6) array of wrenches [f, m] (N, N m) in each joint's local frame, or n values
            each as `external_forces` takes.
        n: number of samples.
        njoints: the model's joint count, universe included.

    Returns:
        n values as `external_forces` returns them (None where there are none).

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

    Args:
        name: the argument's name (for the error).
        value: None, a `pin.StdVec_Force` or a sequence of `pin.Force`, or an (njoints, 6) array of wrenches [f,
            m] (N, N m) in each joint's local frame, universe first.
        njoints: the model's joint count, universe included.

    Returns:
        None, or a `pin.StdVec_Force` of njoints forces.

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
