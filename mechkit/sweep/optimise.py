"""Refine a sweep: scipy.optimize from its best designs, every evaluation a task on the same Dask engine.

The objective is one metric column of the sweep's rows (minimised; `maximise=True` negates it). A
design whose status is not "ok" scores +inf, so the search stays among designs that assemble and
move without a singularity. The swept parameters are searched within their axes' bounds (Nelder-Mead
with bounds, or any bounded `scipy.optimize.minimize` method); the others keep the sweep's values.
Starts run concurrently (one client thread each), so a cluster of several workers evaluates several
searches at once.
"""

from __future__ import annotations

import math
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.optimize import minimize

from mechkit.base.exceptions import InvalidParameters
from mechkit.sweep import store
from mechkit.sweep.engine import dask_client
from mechkit.sweep.evaluate import Chunk, evaluate_chunk
from mechkit.sweep.metrics import Study
from mechkit.sweep.space import DesignSpace


@dataclass(frozen=True)
class Refined:
    """One search.

    Attributes:
        start: the sweep design it started from (parameter -> value) and `start_value` its metric.
        best: the best design found and `value` its metric (the column's unit; sign as stored).
        evaluations: designs evaluated by the search.
        message: scipy's termination message.
    """

    start: dict[str, float]
    start_value: float
    best: dict[str, float]
    value: float
    evaluations: int
    message: str


def optimise(
    out: str | Path,
    column: str,
    *,
    starts: int = 2,
    maximise: bool = False,
    method: str = "Nelder-Mead",
    max_evaluations: int = 60,
    scheduler: str | None = None,
    workers: int | None = None,
) -> list[Refined]:
    """Refine `column` of the sweep in `out` from its `starts` best "ok" designs.

    Args:
        out: the sweep's folder.
        column: the metric column to minimise (or maximise).
        starts: how many of the best designs to start from.
        maximise: maximise instead.
        method: a `scipy.optimize.minimize` method (bounded to the space).
        max_evaluations: designs evaluated per start at most.
        scheduler: a running Dask scheduler (default: as `sweep`).
        workers: worker processes of an embedded cluster.

    Returns:
        One refinement per start: the start, the best design found and its value, the evaluations.

    Raises:
        InvalidParameters: no such column, or no "ok" design to start from.
    """
    manifest = store.read_manifest(out)
    frame = store.read(out)
    if column not in manifest["columns"]:
        raise InvalidParameters("column", column, f"the sweep's metric columns are {', '.join(manifest['columns'])}")
    space = DesignSpace.from_dict(manifest["space"])
    ok = frame[(frame["status"] == "ok") & np.isfinite(frame[column])]
    if ok.empty:
        raise InvalidParameters("column", column, "no design of the sweep has status ok and a finite value")
    sign = -1.0 if maximise else 1.0
    best = ok.assign(_score=sign * ok[column]).nsmallest(starts, "_score")
    names = space.names
    bounds = [(a.lo, a.hi) for a in space.axes]
    base = dict(manifest["base"])
    study, metrics, columns = Study(**manifest["study"]), tuple(manifest["metrics"]), tuple(manifest["columns"])

    with dask_client(scheduler, workers) as client:

        def search(row) -> Refined:
            count = 0

            def objective(x: np.ndarray) -> float:
                nonlocal count
                count += 1
                chunk = Chunk(manifest["mechanism"], base, names, (-count,), np.atleast_2d(x), study, metrics, columns)
                result = client.submit(evaluate_chunk, chunk, pure=False).result()[0]
                value = result[column]
                return sign * value if result["status"] == "ok" and math.isfinite(value) else math.inf

            x0 = np.array([row[n] for n in names], dtype=float)
            found = minimize(
                objective,
                x0,
                method=method,
                bounds=bounds,
                options={"maxfev": max_evaluations} if method == "Nelder-Mead" else {"maxfun": max_evaluations},
            )
            return Refined(
                dict(zip(names, x0.tolist())),
                float(row[column]),
                dict(zip(names, found.x.tolist())),
                sign * float(found.fun),
                count,
                str(found.message),
            )

        with ThreadPoolExecutor(max_workers=len(best)) as pool:
            return list(pool.map(search, [r for _, r in best.iterrows()]))
