"""A moving base's prescribed motion: its position and attitude in time, and the input law that carries it.

A law gives, at a time t (s), the ground body's position x, y, z (m, world) and attitude roll, pitch, yaw
(rad; R = Rz(yaw) Ry(pitch) Rx(roll)): `POSE_COLUMNS`; from a function (values, or values with rates and
accelerations, which are then checked against fourth-order central differences of the values) or from a
CSV file of samples (rates and accelerations from scipy's not-a-knot cubic spline, or given columns
`<name>_dot`, `<name>_ddot`). `carried` joins a base law to a law of the mechanism's own inputs: one
input law over the moving base's root joints and the inputs, for `mechkit.motion.study` and `simulate`.
"""

from __future__ import annotations

import csv
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import scipy.interpolate

from mechkit.base.exceptions import InvalidArgument, MalformedDescription
from mechkit.bases.carrier import BASE_JOINTS
from mechkit.mechanism import Mechanism
from mechkit.motion.inputs import InputLaw

#: A pose's columns, as a law or a CSV file gives them.
POSE_COLUMNS = ("x", "y", "z", "roll", "pitch", "yaw")
#: Their places in the root joints' order `BASE_JOINTS` (x, y, z, yaw, pitch, roll).
_TO_JOINTS = np.array([0, 1, 2, 5, 4, 3])
#: The central-difference step, as a fraction of the sampled span (at least 1 s).
DIFF_STEP = 1e-3
#: Largest disagreement of given rates or accelerations with the differences, relative to their scale.
RATE_CHECK = 1e-4


@dataclass(frozen=True)
class BaseMotion:
    """A base's sampled motion.

    Attributes:
        t: (N,) times (s), strictly increasing.
        values: (N, 6) x, y, z (m), roll, pitch, yaw (rad).
        rates: (N, 6) their rates (m/s, rad/s).
        accelerations: (N, 6) their accelerations (m/s^2, rad/s^2).
        source: where it came from, in words.
    """

    t: np.ndarray
    values: np.ndarray
    rates: np.ndarray
    accelerations: np.ndarray
    source: str = ""

    def joint_arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The root joints' values, rates and accelerations (N, 6), in `BASE_JOINTS` order.

        Returns:
            The three arrays.
        """
        return self.values[:, _TO_JOINTS], self.rates[:, _TO_JOINTS], self.accelerations[:, _TO_JOINTS]


def _times(t: np.ndarray) -> np.ndarray:
    t = np.asarray(t, dtype=float)
    if t.ndim != 1 or len(t) < 2 or not np.all(np.isfinite(t)) or np.any(np.diff(t) <= 0):
        raise InvalidArgument("t", t.shape, "expected at least 2 finite, strictly increasing times (s)")
    return t


def _finite(arg: str, x: np.ndarray, n: int) -> np.ndarray:
    x = np.asarray(x, dtype=float)
    if x.shape != (n, 6) or not np.all(np.isfinite(x)):
        raise InvalidArgument(arg, x.shape, f"expected ({n}, 6) finite numbers: {', '.join(POSE_COLUMNS)}")
    return x


def _check_against(arg: str, given: np.ndarray, estimate: np.ndarray) -> None:
    """Refuse given derivatives that disagree with the differences of the values."""
    scale = max(float(np.abs(estimate).max()), float(np.abs(given).max()), 1e-9)
    worst = float(np.abs(given - estimate).max())
    if worst > RATE_CHECK * scale:
        raise InvalidArgument(arg, f"off by {worst:.3g}", f"disagree with the values' derivative (scale {scale:.3g})")


def from_callable(law: Callable[[float], object], t: np.ndarray, source: str = "callable") -> BaseMotion:
    """A base motion from a function of time, sampled at t.

    Args:
        law: t (s) -> the pose (6,) in `POSE_COLUMNS` order, or (pose, rates, accelerations).
        t: (N,) sample times (s).
        source: where it comes from, in words.

    Returns:
        The motion (rates and accelerations the law's, checked, else fourth-order central differences).

    Raises:
        InvalidArgument: bad times, a pose that is not 6 finite numbers, rates or accelerations that
            disagree with the differences of the poses (relative `RATE_CHECK`).
    """
    if not callable(law):
        raise InvalidArgument("law", law, "expected a function of time")
    t = _times(t)
    h = DIFF_STEP * max(float(np.ptp(t)), 1.0)

    def sample(x: float) -> tuple[np.ndarray, ...]:
        out = law(float(x))
        return tuple(np.asarray(p, dtype=float) for p in (out if isinstance(out, tuple) and len(out) == 3 else (out,)))

    rows = [sample(x) for x in t]
    values = _finite("law", np.array([r[0] for r in rows]), len(t))
    near = {s: _finite("law", np.array([sample(x + s * h)[0] for x in t]), len(t)) for s in (-2, -1, 1, 2)}
    rates = (near[-2] - 8 * near[-1] + 8 * near[1] - near[2]) / (12 * h)
    accs = (-near[-2] + 16 * near[-1] - 30 * values + 16 * near[1] - near[2]) / (12 * h * h)
    if len(rows[0]) == 3:
        given_rates = _finite("law rates", np.array([r[1] for r in rows]), len(t))
        given_accs = _finite("law accelerations", np.array([r[2] for r in rows]), len(t))
        _check_against("law rates", given_rates, rates)
        _check_against("law accelerations", given_accs, accs)
        rates, accs = given_rates, given_accs
    return BaseMotion(t, values, rates, accs, source)


def from_samples(t: np.ndarray, values: np.ndarray, source: str = "samples") -> BaseMotion:
    """A base motion through sampled poses: rates and accelerations of scipy's not-a-knot cubic spline.

    Args:
        t: (N,) times (s).
        values: (N, 6) poses in `POSE_COLUMNS` order (m, rad).
        source: where they come from, in words.

    Returns:
        The motion.

    Raises:
        InvalidArgument: bad times or poses.
    """
    t = _times(t)
    values = _finite("values", values, len(t))
    spline = scipy.interpolate.CubicSpline(t, values, axis=0)
    return BaseMotion(t, values, spline(t, 1), spline(t, 2), source)


def from_csv(path: str | Path) -> BaseMotion:
    """A base motion from a CSV file: a header `t,x,y,z,roll,pitch,yaw` (s, m, rad; a column left out
    is 0), optional `<name>_dot` and `<name>_ddot` columns (checked against the spline's derivatives to
    1 % of their scale, a loose check for units and signs).

    Args:
        path: the file.

    Returns:
        The motion.

    Raises:
        MalformedDescription: an unreadable file, an unknown column, a value that is not a number.
        InvalidArgument: bad times, or given rates that disagree with the values.
    """
    path = Path(path)
    try:
        with path.open(newline="") as stream:
            rows = list(csv.reader(stream))
    except OSError as err:
        raise MalformedDescription(str(path), f"cannot read it: {err}") from None
    if not rows or "t" not in rows[0]:
        raise MalformedDescription(str(path), "needs a header with a column 't' (s)")
    header = [h.strip() for h in rows[0]]
    known = {"t"} | set(POSE_COLUMNS) | {f"{c}{s}" for c in POSE_COLUMNS for s in ("_dot", "_ddot")}
    unknown = sorted(set(header) - known)
    if unknown:
        raise MalformedDescription(str(path), f"unknown columns {unknown}; known: t, {', '.join(POSE_COLUMNS)}")
    try:
        data = np.array([[float(x) for x in row] for row in rows[1:] if row], dtype=float).reshape(-1, len(header))
    except ValueError as err:
        raise MalformedDescription(str(path), f"a value is not a number: {err}") from None
    if not np.isfinite(data).all():
        row, column = np.argwhere(~np.isfinite(data))[0]
        raise MalformedDescription(
            str(path), f"row {row + 1}, column {header[column]!r}: {data[row, column]} is not finite"
        )
    col = {h: data[:, k] for k, h in enumerate(header)}
    n = len(data)

    def block(suffix: str) -> np.ndarray:
        return np.stack([col.get(c + suffix, np.zeros(n)) for c in POSE_COLUMNS], axis=1)

    motion = from_samples(col["t"], block(""), f"CSV {path.name}")
    for suffix, field, arg in (("_dot", "rates", "rates"), ("_ddot", "accelerations", "accelerations")):
        if any(c + suffix in col for c in POSE_COLUMNS):
            given, spline = block(suffix), getattr(motion, field)
            scale = max(float(np.abs(spline).max()), 1e-9)
            if float(np.abs(given - spline).max()) > 1e-2 * scale:
                raise InvalidArgument(f"{path.name} {arg}", "off", "disagree with the spline through the values")
            motion = BaseMotion(**{**motion.__dict__, field: given})
    return motion


def carried(mech: Mechanism, base: BaseMotion, inputs: InputLaw | None = None) -> InputLaw:
    """One input law over a moving base's root joints and the mechanism's own inputs.

    Args:
        mech: a mechanism on a moving base (`mechkit.bases.with_base`).
        base: the base's motion.
        inputs: the law of the mechanism's inputs at the same times (None: every other input held at home).

    Returns:
        The input law (`mechkit.motion.InputLaw`), the root joints first.

    Raises:
        InvalidArgument: a mechanism without the root joints, or an input law on other times.
    """
    if not set(BASE_JOINTS) <= set(mech.model.names):
        raise InvalidArgument("mech", mech.spec.name, "is not on a moving base (mechkit.bases.with_base)")
    values, rates, accs = base.joint_arrays()
    n = len(base.t)
    if inputs is None:
        home = {j: x for j, x in mech.spec.home(mech.params).items() if j not in BASE_JOINTS}
        names, own = tuple(home), np.tile(np.array(list(home.values()), dtype=float), (n, 1))
        own_rates = own_accs = np.zeros_like(own)
    else:
        if len(inputs.t) != n or not np.allclose(inputs.t, base.t, rtol=0, atol=1e-12):
            raise InvalidArgument("inputs", inputs.source, "must be sampled at the base motion's times")
        names, own, own_rates, own_accs = inputs.names, inputs.values, inputs.rates, inputs.accelerations
    return InputLaw(
        BASE_JOINTS + tuple(names),
        base.t,
        np.hstack([values, own]),
        np.hstack([rates, own_rates]),
        np.hstack([accs, own_accs]),
        None,
        f"base {base.source}" + (f", inputs {inputs.source}" if inputs is not None else ""),
    )
