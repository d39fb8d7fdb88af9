"""Input laws of a motion study: the driven joints' coordinates, rates and accelerations over time.

An `InputLaw` holds, for the sample times t (s), the values (rad or m), rates and accelerations of
the joints that fix the assembly (by default those of the mechanism's home inputs: its actuated
joints, plus a passive joint driven by a spring where the mechanism declares one, as the ten-bar's
R5). It comes from a callable of time, from arrays, from a CSV file of time and inputs, from a
registered scene (its poses as warm starts) or from a motion law the mechanism declares
(`MechanismSpec.motion_laws`: the 2T1R's paper law, the ten-bar's deployment). Where rates or
accelerations are not given they are the derivatives of a not-a-knot cubic spline through the values
(arrays, CSV, scenes) or a fourth-order central difference (callables).
"""

from __future__ import annotations

import csv
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import scipy.interpolate

from mechkit.base.exceptions import InvalidParameters, MalformedDescription
from mechkit.mechanism import Mechanism
from mechkit.scenes import scene_poses, scene_times

#: Step of the central differences of a callable law, as a fraction of its duration (1 s if zero).
DIFF_STEP = 1e-3
#: Column suffixes of a CSV law's optional rates and accelerations.
RATE_SUFFIX, ACC_SUFFIX = "_dot", "_ddot"

LawFunction = Callable[[float], Sequence[float] | tuple[Sequence[float], Sequence[float], Sequence[float]]]
"""t (s) -> input values, or (values, rates, accelerations), in the law's joint order."""


@dataclass(frozen=True)
class InputLaw:
    """Sampled input law.

    Attributes:
        names: the driven joints (one-coordinate joints of the mechanism), in column order.
        t: (N,) sample times, s, strictly increasing.
        values: (N, k) joint coordinates (rad or m).
        rates: (N, k) their rates (rad/s or m/s).
        accelerations: (N, k) their accelerations (rad/s^2 or m/s^2).
        guesses: optional (N, nq) configurations near the samples (a scene's poses), warm starts.
        source: where the law came from, for reports.
    """

    names: tuple[str, ...]
    t: np.ndarray
    values: np.ndarray
    rates: np.ndarray
    accelerations: np.ndarray
    guesses: np.ndarray | None = None
    source: str = ""

    def __post_init__(self) -> None:
        n, k = len(self.t), len(self.names)
        if n < 2:
            raise InvalidParameters("t", n, "a motion needs at least 2 samples")
        if len(set(self.names)) != k or k == 0:
            raise InvalidParameters("names", self.names, "need at least one joint, each once")
        t = np.asarray(self.t, dtype=float)
        if t.shape != (n,) or not np.all(np.isfinite(t)) or np.any(np.diff(t) <= 0):
            raise InvalidParameters("t", self.t, "sample times must be finite and strictly increasing")
        for field in ("values", "rates", "accelerations"):
            a = np.asarray(getattr(self, field), dtype=float)
            if a.shape != (n, k) or not np.all(np.isfinite(a)):
                raise InvalidParameters(field, a.shape, f"must be finite of shape ({n}, {k}) (samples, joints)")
            object.__setattr__(self, field, a)
        object.__setattr__(self, "t", t)
        object.__setattr__(self, "names", tuple(self.names))


def default_inputs(mech: Mechanism) -> tuple[str, ...]:
    """The joints that fix the assembly: the keys of the spec's home inputs (actuated first).

    Args:
        mech: the mechanism.

    Returns:
        Joint names.
    """
    home = list(mech.spec.home(mech.params))
    return tuple(mech.actuated) + tuple(j for j in home if j not in mech.actuated)


def _check_names(mech: Mechanism, names: Sequence[str]) -> tuple[str, ...]:
    for joint in names:
        mech.v_index(joint)  # raises InvalidParameters for an unknown joint
    return tuple(names)


def _spline_derivatives(t: np.ndarray, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Rates and accelerations of scipy's not-a-knot cubic spline: through two samples the straight line
    (a constant rate, no acceleration), through three the parabola."""
    spline = scipy.interpolate.CubicSpline(t, values, axis=0)
    return spline(t, 1), spline(t, 2)


def from_arrays(
    mech: Mechanism,
    t: np.ndarray,
    values: np.ndarray,
    rates: np.ndarray | None = None,
    accelerations: np.ndarray | None = None,
    names: Sequence[str] | None = None,
    guesses: np.ndarray | None = None,
    source: str = "arrays",
) -> InputLaw:
    """A law from sampled arrays.

    Args:
        mech: the mechanism.
        t: (N,) times, s.
        values: (N, k) coordinates of `names` (rad or m); (N,) for one joint.
        rates: (N, k) rates (rad/s or m/s), or None for the spline's derivative (with `accelerations`).
        accelerations: (N, k) accelerations (rad/s^2 or m/s^2), or None (both or neither).
        names: the driven joints (default: `default_inputs`).
        guesses: optional (N, nq) configurations near the samples.
        source: where the law comes from, in words (kept in the result).

    Returns:
        The law.

    Raises:
        InvalidParameters: unknown or repeated joints, times that are not at least 2 finite increasing values,
            arrays of the wrong shape or not finite, rates without accelerations (or the reverse).
    """
    names = _check_names(mech, names or default_inputs(mech))
    t = np.asarray(t, dtype=float)
    if t.ndim != 1 or len(t) < 2 or not np.all(np.isfinite(t)) or np.any(np.diff(t) <= 0):
        raise InvalidParameters("t", t.shape, "sample times must be at least 2, finite and strictly increasing")
    values = np.asarray(values, dtype=float).reshape(len(t), -1) if np.ndim(values) == 1 else np.asarray(values, float)
    if (rates is None) != (accelerations is None):
        raise InvalidParameters("rates/accelerations", None, "give both or neither")
    if values.shape != (len(t), len(names)):
        raise InvalidParameters("values", values.shape, f"expected ({len(t)}, {len(names)}) for {list(names)}")
    for what, x in (("values", values), ("rates", rates), ("accelerations", accelerations)):
        if x is not None and not np.all(np.isfinite(np.asarray(x, dtype=float))):
            raise InvalidParameters(what, "NaN or inf", "every sample must be a finite number")
    if rates is None:
        rates, accelerations = _spline_derivatives(t, values)
    if guesses is not None:
        guesses = np.asarray(guesses, dtype=float)
        if guesses.shape != (len(t), mech.model.nq):
            raise InvalidParameters("guesses", guesses.shape, f"expected ({len(t)}, {mech.model.nq})")
    return InputLaw(names, t, values, np.asarray(rates, float), np.asarray(accelerations, float), guesses, source)


def from_callable(
    mech: Mechanism, law: LawFunction, t: np.ndarray, names: Sequence[str] | None = None, source: str = "callable"
) -> InputLaw:
    """A law from a function of time, sampled at t (s).

    `law(t)` returns the values, or (values, rates, accelerations); with values only, rates and
    accelerations are fourth-order central differences with step `DIFF_STEP` of the duration.

    Args:
        mech: the mechanism.
        law: a function of t (s) giving the values of `names` (rad or m), or (values, rates, accelerations).
        t: (N,) sample times, s.
        names: the driven joints (default: `default_inputs`).
        source: where the law comes from, in words.

    Returns:
        The law.

    Raises:
        InvalidParameters: fewer than 2 times, unknown joints, or values of the wrong size.
    """
    names = _check_names(mech, names or default_inputs(mech))
    t = np.asarray(t, dtype=float)
    if t.ndim != 1 or len(t) < 2:
        raise InvalidParameters("t", t.shape, "need a 1-D array of at least 2 times")

    def sample(x: float) -> tuple[np.ndarray, ...]:
        out = law(float(x))
        parts = out if isinstance(out, tuple) and len(out) == 3 else (out,)
        return tuple(np.atleast_1d(np.asarray(p, dtype=float)) for p in parts)

    first = sample(t[0])
    if len(first) == 3:
        rows = [first] + [sample(x) for x in t[1:]]
        values, rates, accs = (np.array([r[i] for r in rows]) for i in range(3))
    else:
        h = DIFF_STEP * (float(np.ptp(t)) or 1.0)
        values = np.array([first[0]] + [sample(x)[0] for x in t[1:]])
        near = {s: np.array([sample(x + s * h)[0] for x in t]) for s in (-2, -1, 1, 2)}
        rates = (near[-2] - 8 * near[-1] + 8 * near[1] - near[2]) / (12 * h)
        accs = (-near[-2] + 16 * near[-1] - 30 * values + 16 * near[1] - near[2]) / (12 * h * h)
    if values.shape[1:] != (len(names),):
        raise InvalidParameters("law", values.shape, f"must return {len(names)} values for {list(names)}")
    return InputLaw(names, t, values, rates, accs, None, source)


def from_csv(mech: Mechanism, path: str | Path) -> InputLaw:
    """A law from a CSV file: a header with `t` (s) and one column per driven joint (rad or m); optional
    `<joint>_dot` and `<joint>_ddot` columns give rates and accelerations (else the spline's). Lines
    starting with `#` are comments.

    Args:
        mech: the mechanism.
        path: the CSV file.

    Returns:
        The law (source: the file's name).

    Raises:
        MalformedDescription: the file is missing or not text, has no `t` column or no joint column, a
            column twice, rate or acceleration columns not given for every joint column (or given for
            none), a row of another length than the header, or a cell that is not a finite number (named
            by its line and column).
    """
    path = Path(path)
    try:
        with path.open(newline="") as handle:
            lines = [(k, line) for k, line in enumerate(handle, 1) if line.strip() and not line.startswith("#")]
    except (OSError, UnicodeDecodeError) as err:
        why = getattr(err, "strerror", None) or f"not a text file ({err.reason})"
        raise MalformedDescription(str(path), f"cannot read the input law: {why}") from None
    rows = [(k, row) for (k, _), row in zip(lines, csv.reader(line for _, line in lines))]
    if len(rows) < 3 or "t" not in [h.strip() for h in rows[0][1]]:
        raise MalformedDescription(str(path), "needs a header with a 't' column and at least 2 rows")
    header = _header(path, [h.strip() for h in rows[0][1]])
    data = np.array([_row(path, k, row, header) for k, row in rows[1:]], dtype=float)
    col = {h: data[:, i] for i, h in enumerate(header)}
    names = tuple(h for h in header if h != "t" and not h.endswith((RATE_SUFFIX, ACC_SUFFIX)))
    has_rates = names[0] + RATE_SUFFIX in col  # `_header`: for every joint or for none
    rates = np.column_stack([col[n + RATE_SUFFIX] for n in names]) if has_rates else None
    accs = np.column_stack([col[n + ACC_SUFFIX] for n in names]) if has_rates else None
    values = np.column_stack([col[n] for n in names])
    return from_arrays(mech, col["t"], values, rates, accs, names=names, source=str(path))


def _header(path: Path, header: list[str]) -> list[str]:
    """A law's header, checked: each column once, at least one joint, the rate and acceleration columns
    of every joint or of none, none without its joint (a column nobody reads would be ignored)."""
    for h in header:
        if not h or header.count(h) > 1:
            raise MalformedDescription(str(path), f"column {h!r} is {'empty' if not h else 'given twice'}")
    names = [h for h in header if h != "t" and not h.endswith((RATE_SUFFIX, ACC_SUFFIX))]
    if not names:
        raise MalformedDescription(str(path), "needs a column per driven joint besides 't'")
    derived = {h for h in header if h != "t" and h.endswith((RATE_SUFFIX, ACC_SUFFIX))}
    expected = {n + s for n in names for s in (RATE_SUFFIX, ACC_SUFFIX)} if derived else set()
    if derived != expected:
        odd = sorted(derived - expected) or sorted(expected - derived)
        raise MalformedDescription(
            str(path),
            f"rate and acceleration columns ({', '.join(odd)}): give <joint>{RATE_SUFFIX} and "
            f"<joint>{ACC_SUFFIX} for every joint column, or none",
        )
    return header


def _row(path: Path, line: int, row: list[str], header: list[str]) -> list[float]:
    """One row of a law: as many cells as the header, each a finite number."""
    if len(row) != len(header):
        raise MalformedDescription(f"{path}: line {line}", f"{len(row)} cells, the header has {len(header)}")
    out = []
    for cell, column in zip(row, header):
        try:
            value = float(cell)
        except ValueError:
            raise MalformedDescription(
                f"{path}: line {line}", f"column {column!r}: {cell.strip()!r} is not a number"
            ) from None
        if not math.isfinite(value):
            raise MalformedDescription(
                f"{path}: line {line}", f"column {column!r}: {cell.strip()!r} is not a finite number"
            )
        out.append(value)
    return out


def from_scene(mech: Mechanism, scene: str, names: Sequence[str] | None = None) -> InputLaw:
    """A law from a registered scene: its poses' input coordinates, at the scene's time axis where the
    mechanism declares one (`mechkit.scenes.scene_times`), else one second per pose; poses as guesses.

    Args:
        mech: the mechanism.
        scene: one of its scenes (`mechkit.scenes.scenes`).
        names: the driven joints (default: `default_inputs`).

    Returns:
        The law.

    Raises:
        InvalidParameters: no such scene.
        MalformedDescription: the scene's poses or times are not valid.
    """
    poses = np.array(scene_poses(mech, scene))
    names = _check_names(mech, names or default_inputs(mech))
    t = scene_times(mech, scene, len(poses))
    values = poses[:, [mech.q_index(n) for n in names]]
    return from_arrays(mech, t, values, names=names, guesses=poses, source=f"scene {scene}")


def from_law(mech: Mechanism, name: str, samples: int | None = None) -> InputLaw:
    """A motion law the mechanism declares (`MechanismSpec.motion_laws`).

    Args:
        mech: the mechanism.
        name: the law's name.
        samples: how many samples (default: the law's own count).

    Returns:
        The law.

    Raises:
        InvalidParameters: the mechanism declares no law of that name.
    """
    declared = mech.spec.motion_laws
    if name not in declared:
        raise InvalidParameters(
            "law", name, f"{mech.spec.name} declares the motion laws: {', '.join(declared) or 'none'}"
        )
    law = declared[name].sample(mech, samples)
    return from_arrays(
        mech, law.t, law.values, law.rates, law.accelerations, names=law.joints, guesses=law.guesses, source=law.source
    )


def resample(law: InputLaw, samples: int) -> InputLaw:
    """The law at `samples` uniform times over its span (cubic splines of values, rates and
    accelerations); guesses from the nearest original sample.

    Args:
        law: the law.
        samples: how many samples (>= 2).

    Returns:
        The resampled law.

    Raises:
        InvalidParameters: fewer than 2 samples.
    """
    if samples < 2:
        raise InvalidParameters("samples", samples, "need at least 2")
    t = np.linspace(law.t[0], law.t[-1], samples)
    parts = [
        scipy.interpolate.CubicSpline(law.t, x, axis=0)(t)
        if len(law.t) >= 4
        else scipy.interpolate.interp1d(law.t, x, axis=0)(t)
        for x in (law.values, law.rates, law.accelerations)
    ]
    guesses = None
    if law.guesses is not None:
        after = np.clip(np.searchsorted(law.t, t), 1, len(law.t) - 1)
        nearest = np.where(t - law.t[after - 1] <= law.t[after] - t, after - 1, after)
        guesses = law.guesses[nearest]
    return InputLaw(law.names, t, *parts, guesses, law.source)
