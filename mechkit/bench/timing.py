"""Timing: seconds per call in a calibrated loop (one process, garbage collector off), a method's row
(error, then time), and the ratio columns.

The ratio columns: "x fastest" = time / time of the fastest method whose error is at most
max(10 x this error, `EQUAL_ACCURACY_FLOOR`) (the fastest of equal or better accuracy; an "efforts
only" inverse dynamics is not counted against one that gives reactions); "x base" = time / time of
the quantity's baseline (`mechkit.bench.methods.BASELINES`: the core's default method; none for
inverse kinematics, which the core does not compute).
"""

from __future__ import annotations

import gc
import time
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from mechkit.base.exceptions import MechkitError
from mechkit.bench.errors import acceleration_error, assembly_error, inverse_error
from mechkit.bench.methods import BASELINES, Method, References
from mechkit.bench.results import Row
from mechkit.bench.sampling import Sample
from mechkit.catalog.contract import BENCH_QUANTITIES

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

#: Errors at or below this count as one accuracy class (machine precision) for the ratio column.
EQUAL_ACCURACY_FLOOR = 1e-12


def time_per_call(fn: Callable[[Any], Any], samples: Sequence[Any], budget_s: float, repeats: int) -> np.ndarray:
    """Seconds per call of fn cycling over the samples: one value per repeat.

    The loop count is calibrated so that each repeat lasts about budget_s / repeats.

    Args:
        fn: the call, of one sample.
        samples: the samples, cycled.
        budget_s: seconds of timing over all repeats.
        repeats: repeats.

    Returns:
        Seconds per call, shape (repeats,).
    """
    gc_was = gc.isenabled()
    gc.disable()
    try:
        t0 = time.perf_counter()
        fn(samples[0])
        once = max(time.perf_counter() - t0, 1e-7)
        loops = max(1, int(budget_s / repeats / once))
        n = len(samples)
        out = np.empty(repeats)
        for r in range(repeats):
            start = time.perf_counter_ns()
            for i in range(loops):
                fn(samples[i % n])
            out[r] = (time.perf_counter_ns() - start) * 1e-9 / loops
    finally:
        if gc_was:
            gc.enable()
    return out


def paired_ratio(
    fa: Callable[[Any], Any], fb: Callable[[Any], Any], samples: Sequence[Any], budget_s: float, repeats: int
) -> float:
    """Median over repeats of t(fa) / t(fb), the two timed back to back in each repeat (load cancels).

    Args:
        fa: the call timed on top.
        fb: the call timed beneath.
        samples: the samples, cycled.
        budget_s: seconds of timing over all repeats.
        repeats: repeats.

    Returns:
        The median ratio (-).
    """
    ratios = [
        time_per_call(fa, samples, budget_s / repeats / 2, 1)[0]
        / time_per_call(fb, samples, budget_s / repeats / 2, 1)[0]
        for _ in range(repeats)
    ]
    return float(np.median(ratios))


def measure(
    mech: Mechanism, method: Method, samples: list[Sample], refs: References, budget_s: float, repeats: int
) -> Row:
    """Error on every sample, then time per call; a raised MechkitError becomes the row's outcome.

    Args:
        mech: the mechanism.
        method: the method.
        samples: the bench's states.
        refs: the references at those states.
        budget_s: seconds of timing.
        repeats: timing repeats.

    Returns:
        The method's row: worst error over the samples, median and spread of its time per call, its outcome.
    """
    row = Row(mech.spec.name, method)
    errors = []
    try:
        for i, s in enumerate(samples):
            result = method.run(mech, s)
            if method.quantity == "assembly":
                errors.append(assembly_error(result, refs.q[i]))
            elif method.quantity == "inverse_kinematics":
                errors.append(assembly_error(result, refs.inputs[i]))
            elif method.quantity == "forward_dynamics":
                errors.append(acceleration_error(result, refs.a[i]))
            else:
                err, row.note = inverse_error(result, refs.inverse[i], mech.actuated)
                errors.append(err)
    except (MechkitError, FloatingPointError, np.linalg.LinAlgError, TypeError) as err:
        row.outcome = f"raises {type(err).__name__}: {err}"
        return row
    except Exception as err:  # a peer's own failure is its row's outcome; ours propagate
        if not method.peer:
            raise
        row.outcome = f"raises {type(err).__name__}: {err}"
        return row
    row.error = max(errors)
    if not np.isfinite(row.error):
        row.outcome = "non-finite result"
        return row
    times = time_per_call(lambda s: method.run(mech, s), samples, budget_s, repeats)
    row.median_s = float(np.median(times))
    row.p25_s, row.p75_s = (float(x) for x in np.percentile(times, [25, 75]))
    return row


def ratios(rows: list[Row]) -> None:
    """Fill the "x fastest" and "x base" columns of the measured rows (in place).

    Args:
        rows: the rows of one or more mechanisms' benches.
    """
    for quantity in BENCH_QUANTITIES:
        ok = [r for r in rows if r.method.quantity == quantity and r.outcome == "ok"]
        base = [r for r in ok if r.method.name == BASELINES.get(quantity)]
        for r in ok:
            limit = max(10.0 * r.error, EQUAL_ACCURACY_FLOOR)
            # a method that gives efforts only is no yardstick for one that gives every reaction
            candidates = [o for o in ok if o.error <= limit and (o.note != "efforts only" or r.note == "efforts only")]
            r.x_fastest = r.median_s / min(o.median_s for o in candidates)
            if base:
                r.x_base = r.median_s / base[0].median_s
