"""Checks of arguments that name joints: joint names, per-joint values (a ball joint's rotation vector among
them), the inputs of N samples and external forces per joint, each raising `InvalidArgument` that says
which argument and why (the scalar and state checks they build on are `mechkit.base.arguments`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pinocchio as pin

from mechkit.base.arguments import array, number
from mechkit.base.exceptions import InvalidArgument


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


def joint_values(
    name: str, value: Any, names: Sequence[str], known: Sequence[str], sizes: Mapping[str, int] | None = None
) -> dict[str, float | np.ndarray]:
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
        out[joint] = float(flat[i]) if w == 1 else flat[i : i + w].copy()
        i += w
    return out


def sample_inputs(
    name: str, values: Any, names: Sequence[str], n: int, known: Sequence[str], sizes: Mapping[str, int] | None = None
) -> tuple[list[str], np.ndarray]:
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
                cols.append(
                    array(
                        f"{name}[{k!r}]", np.reshape(v, (n, width[k])) if np.size(v) == n * width[k] else v, width[k]
                    ).reshape(n, width[k])
                )
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
        raise InvalidArgument(
            name, value, f"expected one force per joint ({njoints}, universe first), got {rows.shape[0]}"
        )
    if not np.all(np.isfinite(rows)):
        raise InvalidArgument(name, value, "must be finite")
    out = pin.StdVec_Force()
    for row in rows:
        out.append(pin.Force(row[:3].copy(), row[3:].copy()))
    return out
