"""Cost against model size: the core's methods timed across mechanisms, fitted t ~ nv^p."""

from __future__ import annotations

import numpy as np

from mechkit.bench.methods import BASELINES
from mechkit.bench.results import MechanismBench
from mechkit.bench.timing import time_per_call

#: Core methods timed for the cost-vs-size fit.
SCALE_METHODS = (
    BASELINES["assembly"],
    BASELINES["forward_dynamics"],
    "raw pin.constraintDynamics (mu=1e-9)",
    "dense KKT (independent rows)",
    BASELINES["inverse_dynamics"],
    "constrained RNEA, no determinacy",
)

ScaleFit = tuple[str, list[tuple[str, int, float]], float]
"""(method, [(mechanism, nv, seconds per call)] sorted by nv, exponent p of t ~ nv^p)."""


def scale_fits(results: list[MechanismBench], budget_s: float = 0.02, rounds: int = 7) -> list[ScaleFit]:
    """Cost vs model size: one `ScaleFit` per method of SCALE_METHODS.

    The mechanisms are timed round-robin (each round times every mechanism once) so that a change
    of machine load hits all of them alike; the median over rounds is fitted by least squares in
    log-log. Methods measured on fewer than 3 mechanisms are left out.

    Args:
        results: the benches (their mechanisms, samples and rows).
        budget_s: seconds of timing per mechanism and round.
        rounds: rounds over the mechanisms.

    Returns:
        (method, [(mechanism, nv, median seconds per call)] by nv, fitted exponent p) per method.
    """
    out = []
    for name in SCALE_METHODS:
        runs = [
            (b, r.method)
            for b in results
            for r in b.rows
            if r.method.name == name and r.outcome == "ok" and b.mech is not None
        ]
        if len(runs) < 3:
            continue
        times = np.empty((rounds, len(runs)))
        for k in range(rounds):
            for i, (b, method) in enumerate(runs):
                times[k, i] = time_per_call(lambda s, b=b, f=method.run: f(b.mech, s), b.samples, budget_s, 1)[0]
        med = np.median(times, axis=0)
        pts = sorted(((b.name, b.nv, float(t)) for (b, _), t in zip(runs, med)), key=lambda p: p[1])
        nvs = np.array([p[1] for p in pts], dtype=float)
        if np.ptp(np.log(nvs)) > 0:
            slope = float(np.polyfit(np.log(nvs), np.log([p[2] for p in pts]), 1)[0])
            out.append((name, pts, slope))
    return out
