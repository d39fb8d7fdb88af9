"""The 2T1R's studies, as data (`SPEC.studies`; figures in `figures`, numbers in
docs/mechanisms/parallel_2t1r.md): the three inverse-dynamics methods along the paper's motion law
(`comparison`), and the singular studies (`singular`): the motion law's singular start and theta_1
driven onto theta_2.

The singular studies record every method of `compare.evaluate` per sample, NaN where a method
raised, and the failures with their messages: a singular pose must give a clear error, never a
silent NaN.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import MechkitError
from mechkit.mechanism import Mechanism
from mechkit.mechanisms.parallel_2t1r.branch import EXAMPLE_INPUTS, INPUTS, assembled_pose
from mechkit.mechanisms.parallel_2t1r.compare import (
    QUANTITIES,
    Comparison,
    compare_along,
    evaluate,
    pinocchio_motion,
)
from mechkit.mechanisms.parallel_2t1r.joint_state import joint_positions
from mechkit.mechanisms.parallel_2t1r.motion_law import motion_law, motion_law_times, state_at
from mechkit.mechanisms.parallel_2t1r.rates import at_rest, jacobians

#: Singular-approach study: theta_2, theta_3 held at the example's 20 and 30 deg while theta_1 is
#: driven up to theta_2: at theta_1 = theta_2 the chord B1B2 equals A1A2 = l1 = 2 l2, the
#: five-bar's distal links are collinear (C1 a double root of eq. (7)).
SINGULAR_HELD = EXAMPLE_INPUTS[1:]


@dataclass(frozen=True)
class Study:
    """Series along an approach parameter x (n,): values by series name (n,), NaN where the method
    raised, and the failures by series name: (x, error message) of every sample where it raised."""

    x: np.ndarray
    values: dict[str, np.ndarray]
    failures: dict[str, list[tuple[float, str]]]


def _study(x: np.ndarray, samples: Iterable[tuple[dict[str, float], dict[str, str]]]) -> Study:
    """Collect `evaluate`-style (values, failures) per sample into a `Study`."""
    collected: list[tuple[dict[str, float], dict[str, str]]] = list(samples)
    names = sorted({k for values, _ in collected for k in values})
    values = {k: np.array([v.get(k, np.nan) for v, _ in collected], dtype=float) for k in names}
    failures: dict[str, list[tuple[float, str]]] = {}
    for xi, (_, failed) in zip(x, collected):
        for method, why in failed.items():
            failures.setdefault(method, []).append((float(xi), why))
    return Study(np.asarray(x, dtype=float), values, failures)


def singular_approach(mech: Mechanism, deltas: np.ndarray) -> Study:
    """At rest under gravity, theta_1 = theta_2 - delta (rad) with `SINGULAR_HELD`: both variants.

    Series: "<method>:<quantity>" as in `evaluate` for the paper's three motors, the same prefixed
    "redundant/" for R41 driven too (minimum-norm torques), and "cond_Jp" (analytic J_p). Pinocchio
    assembles from the analytic configuration and is evaluated at rest.

    Args:
        mech: the 2T1R.
        deltas: distances of theta_1 from theta_2, rad.

    Returns:
        The study: series by name, failures by method.
    """
    p = mech.params

    def sample(delta: float):
        theta = np.array([SINGULAR_HELD[0] - delta, *SINGULAR_HELD])
        pose, theta4, _ = assembled_pose(p.dims, theta)
        s = at_rest(pose, theta, theta4)
        values, failed = {"cond_Jp": float(np.linalg.cond(jacobians(p.dims, s.theta, pose)[0]))}, {}
        try:
            q = mech.assemble(dict(zip(INPUTS, theta)), guess=joint_positions(p, s))
            motion = (q, np.zeros(mech.model.nv), np.zeros(mech.model.nv))
        except MechkitError as err:
            motion, failed["pinocchio"] = None, str(err)
        for redundant, prefix in ((False, ""), (True, "redundant/")):
            v, f, _ = evaluate(mech, s, motion, redundant, determinacy=True)
            values |= {prefix + k: x for k, x in v.items()}
            failed |= {prefix + k: x for k, x in f.items()}
        return values, failed

    return _study(deltas, (sample(float(d)) for d in deltas))


def start_of_motion(mech: Mechanism, times: np.ndarray) -> Study:
    """The motion law near its singular start (t -> 0+): three motors, Pinocchio's own motion.

    Series as in `evaluate` plus "cond_Jp" and "analytic:x_ddot" (|platform acceleration| of eq.
    (15)); a sample whose analytic state or Pinocchio motion raises is recorded as a failure.

    Args:
        mech: the 2T1R.
        times: times near the start, s.

    Returns:
        The study: series by name, failures by method.
    """
    p = mech.params

    def sample(t: float):
        theta, rates, acc = motion_law(t)
        pose, theta4, disc = assembled_pose(p.dims, theta)
        values = {
            "fk_discriminant": disc,
            "cond_Jp": float(np.linalg.cond(jacobians(p.dims, np.append(theta, theta4), pose)[0])),
        }
        failed = {}
        try:
            s = state_at(p, theta, rates, acc)
        except MechkitError as err:
            failed["analytic"] = str(err)
            s = at_rest(pose, theta, theta4)
        values["analytic:x_ddot"] = float(np.linalg.norm(s.x_ddot)) if "analytic" not in failed else np.nan
        try:
            motion = pinocchio_motion(mech, theta, rates, acc, joint_positions(p, s))
        except MechkitError as err:
            motion, failed["pinocchio"] = None, str(err)
        v, f, _ = evaluate(mech, s, motion, determinacy=True)
        if "analytic" in failed:  # SOC and classic ran on the state at rest: not the motion's values
            v = {k: x for k, x in v.items() if k.startswith("pinocchio")}
            f |= {m: "no analytic motion state" for m in ("soc", "classic") if m not in f}
        return values | v, failed | f

    return _study(times, (sample(float(t)) for t in times))


#: Regular samples of the motion law in the comparison (0.01 s steps).
COMPARISON_SAMPLES = 500
#: Times (s) after the motion law's singular start, and offsets theta_2 - theta_1 (rad) of the approach.
START_TIMES = np.logspace(-5, 0, 11)
APPROACH_DELTAS = np.append(np.logspace(-1, -8, 15), 0.0)


def comparison(mech: Mechanism, samples: int = COMPARISON_SAMPLES) -> Comparison:
    """Pinocchio, SOC and classic virtual work at `samples` regular times of the motion law in (0, 5] s.

    Args:
        mech: the 2T1R.
        samples: how many times.

    Returns:
        The comparison.
    """
    return compare_along(mech, motion_law_times(samples))


def comparison_lines(cmp: Comparison) -> list[str]:
    """Per quantity, its largest magnitude and each method's error relative to it; the joints' agreement.

    Args:
        cmp: the comparison.

    Returns:
        Text lines.
    """
    peak = np.max(np.abs(cmp.values["pinocchio"]), axis=0)
    soc, classic = cmp.relative_error("soc"), cmp.relative_error("classic")
    out = [
        (
            f"{len(cmp.times)} samples, t = {cmp.times[0]:g}..{cmp.times[-1]:g} s; relative to each quantity's "
            "largest magnitude:"
        )
    ]
    for k, name in enumerate(QUANTITIES):
        other = "-" if np.isnan(classic[k]) else f"{classic[k]:.1e}"
        out.append(f"  {name:7s} max {peak[k]:8.3f}: SOC vs Pinocchio {soc[k]:.1e}, classic vs Pinocchio {other}")
    out.append(f"analytic vs Pinocchio joint angles: {cmp.kinematics_error.max():.1e} rad")
    return out


@dataclass(frozen=True)
class SingularStudies:
    """The motion law near its singular start, and theta_1 driven onto theta_2 (`start_of_motion`,
    `singular_approach`)."""

    start: Study
    approach: Study


def singular(mech: Mechanism, times: np.ndarray = START_TIMES, deltas: np.ndarray = APPROACH_DELTAS) -> SingularStudies:
    """Both singular studies: `start_of_motion` at `times` (s), `singular_approach` at `deltas` (rad).

    Args:
        mech: the 2T1R.
        times: times near the start, s.
        deltas: distances from the singular pose, rad.

    Returns:
        Both studies.
    """
    return SingularStudies(start_of_motion(mech, times), singular_approach(mech, deltas))


def singular_lines(s: SingularStudies) -> list[str]:
    """Where each method first raised in each study, and why.

    Args:
        s: the singular studies.

    Returns:
        Text lines.
    """
    out = []
    for name, study, unit in (
        ("motion law, t -> 0+", s.start, "t (s)"),
        ("theta_1 onto theta_2", s.approach, "theta_2 - theta_1 (rad)"),
    ):
        out.append(f"{name}: {len(study.x)} samples, {unit} {study.x.min():.1e}..{study.x.max():.1e}")
        out += [
            f"  {method} raises first at {failed[0][0]:.1e}: {failed[0][1][:120]}"
            for method, failed in study.failures.items()
        ]
    return out
