"""The sweep engine: designs in chunks, one Dask task per chunk, rows written as chunks finish.

With no scheduler address (argument or `MECHKIT_DASK_SCHEDULER`), an embedded `LocalCluster` of
worker processes (one thread each) on 127.0.0.1 starts and stops with the sweep; with one, the same
tasks go to that running cluster (`cluster`). The client writes each finished chunk's part file
(`store`), so a sweep killed at any moment resumes with `resume=True`; a sweep the cluster cannot
finish (the scheduler lost, no worker for too long) stops with `SweepStopped`, saying what is saved,
and resumes the same way. While it runs, Dask's log records go to `sweep.log` in the results folder.
"""

from __future__ import annotations

import math
import os
import time
from collections import Counter
from collections.abc import Callable
from dataclasses import asdict, dataclass, fields
from pathlib import Path

from mechkit.base.exceptions import InvalidParameters, MechkitError
from mechkit.catalog.registry import get_spec
from mechkit.loading import load
from mechkit.sweep import store
from mechkit.sweep.cluster import (
    WAIT_WORKERS,
    ClusterError,
    ClusterState,
    Monitor,
    check_options,
    dask_client,
)
from mechkit.sweep.evaluate import STATUSES, Chunk, evaluate_chunk
from mechkit.sweep.log_file import LOG, log_to
from mechkit.sweep.metrics import Study
from mechkit.sweep.space import DesignSpace
from mechkit.sweep.specific import resolve


class SweepStopped(MechkitError):
    """The cluster could not finish the sweep; what was saved stays, and `resume=True` continues it.

    Attributes:
        cause: what the cluster did (`SchedulerLost`, `NoWorkers`, `SchedulerUnreachable`, `TaskFailed`).
        out: the results folder.
        saved: designs whose rows are on disk.
        designs: designs in the sweep.
    """

    def __init__(self, cause: ClusterError, out: Path, saved: int, designs: int):
        self.cause, self.out, self.saved, self.designs = cause, out, saved, designs
        super().__init__(f"{cause}; {saved} of {designs} designs are saved in {out} (details in {out / LOG})")


@dataclass(frozen=True)
class SweepSummary:
    """What a sweep run did.

    Attributes:
        out: the results folder.
        designs: designs in the sweep.
        evaluated: designs evaluated by this run (the rest were done by an earlier, resumed run).
        statuses: status -> number of rows in the whole dataset after this run.
        seconds: wall time of this run (s), cluster start included.
        workers: the most Dask workers that served the run at once.
    """

    out: Path
    designs: int
    evaluated: int
    statuses: dict[str, int]
    seconds: float
    workers: int


def _check_axes(mechanism: str, space: DesignSpace, base: dict) -> None:
    known = {f.name: f for f in fields(get_spec(mechanism).params)}
    for name in space.names:
        if name not in known or isinstance(known[name].default, (bool, str)):
            numeric = [n for n, f in known.items() if not isinstance(f.default, (bool, str))]
            raise InvalidParameters(
                "grid", name, f"not a numeric parameter of {mechanism}; they are {', '.join(numeric)}"
            )
        if name in base:
            raise InvalidParameters("set", name, "is swept: it cannot also be fixed")


def planned_columns(mechanism: str, metrics: tuple[str, ...] | None, base: dict) -> tuple[str, ...]:
    """The metric columns a sweep of `mechanism` fills (known before any design is evaluated).

    Args:
        mechanism: registry name (or description file).
        metrics: metric names (None: the mechanism's default set).
        base: fixed parameter overrides of every design.

    Returns:
        The column names, in the order of the rows.

    Raises:
        InvalidParameters: an unknown metric or parameter.
    """
    reference = load(mechanism, **base)
    return tuple(c for m in resolve(mechanism, metrics) for c in m.columns(reference))


def sweep(
    mechanism: str,
    space: DesignSpace,
    out: str | Path,
    study: Study | None = None,
    metrics: tuple[str, ...] | None = None,
    *,
    base: dict | None = None,
    resume: bool = False,
    scheduler: str | None = None,
    workers: int | None = None,
    chunk_size: int | None = None,
    fast: bool = True,
    wait_workers: float = WAIT_WORKERS,
    dashboard: bool = False,
    progress: Callable[[int], None] | None = None,
    watch: Callable[[ClusterState], None] | None = None,
) -> SweepSummary:
    """Evaluate every design of `space` on Dask and write one row per design to `out`.

    Args:
        mechanism: registry name.
        space: the designs.
        out: results folder (created; must be empty unless resuming).
        study: the motion each design runs (default `Study()`).
        metrics: metric names (default: the mechanism's default set).
        base: fixed parameter overrides of every design.
        resume: continue the sweep already in `out` (the same arguments), evaluating only the
            chunks without a part file.
        scheduler: address of a running Dask scheduler (default: `$MECHKIT_DASK_SCHEDULER`, else an
            embedded LocalCluster of `workers` processes, default the CPU count); a `tls://` address
            uses the certificates of Dask's configuration (`mechkit.sweep.cluster.tls_config`).
        workers: worker processes of the embedded cluster.
        chunk_size: designs per task (default: about 4 tasks per worker, at most 50 designs).
        fast: build designs through the template cache (False: xacro for each design).
        wait_workers: how long (s) the cluster may have no worker, at the start or later, before the
            sweep stops.
        dashboard: the embedded cluster serves Dask's dashboard on 127.0.0.1.
        progress: called with the number of designs finished, chunk by chunk.
        watch: called with the `ClusterState` when the sweep starts and whenever the number of workers
            changes.

    Returns:
        What the run did.

    Raises:
        InvalidParameters: a swept or fixed parameter the mechanism does not have, a bad chunk size,
            a results folder that holds another sweep (or a sweep, without `resume`), cluster options
            `check_options` refuses (checked before the folder is written).
        MethodUnavailable: `dashboard` without bokeh installed.
        SweepStopped: the cluster could not finish the sweep (scheduler unreachable or lost, no worker
            for `wait_workers` seconds, a task that failed on the cluster); the rows finished are saved.
    """
    start = time.perf_counter()
    study, base = study or Study(), dict(base or {})
    _check_axes(mechanism, space, base)
    chosen = resolve(mechanism, metrics)
    columns = planned_columns(mechanism, metrics, base)
    designs = space.designs()
    n_workers = workers or os.cpu_count() or 1
    size = chunk_size or max(1, min(50, math.ceil(len(designs) / (4 * n_workers))))
    if size < 1:
        raise InvalidParameters("chunk_size", size, "must be >= 1")
    manifest = {
        "mechanism": mechanism,
        "base": {k: str(v) for k, v in base.items()},
        "space": space.to_dict(),
        "study": asdict(study),
        "metrics": [m.name for m in chosen],
        "columns": list(columns),
        "chunk_size": size,
        "designs": len(designs),
    }
    check_options(scheduler, dashboard=dashboard, wait_workers=wait_workers)
    out = Path(out)
    done = store.prepare(out, manifest, designs, resume)
    row_schema = store.schema(space.names, columns)
    chunks = range(math.ceil(len(designs) / size))
    pending = [k for k in chunks if k not in done]
    evaluated = 0
    if progress is not None and done:
        progress(sum(len(range(k * size, min((k + 1) * size, len(designs)))) for k in done))
    try:
        with log_to(out / LOG), dask_client(scheduler, workers, dashboard=dashboard) as client:
            monitor = Monitor(client, wait_workers, watch, client.dashboard_link if dashboard else None)
            futures = {}
            for k in pending:
                idx = tuple(range(k * size, min((k + 1) * size, len(designs))))
                task = Chunk(
                    mechanism,
                    base,
                    space.names,
                    idx,
                    designs[list(idx)],
                    study,
                    tuple(m.name for m in chosen),
                    columns,
                    fast,
                )
                futures[client.submit(evaluate_chunk, task, pure=False)] = k
            for future, rows in monitor.results(futures):
                store.write_part(out, futures[future], rows, row_schema)
                evaluated += len(rows)
                if progress is not None:
                    progress(len(rows))
    except ClusterError as err:
        raise SweepStopped(err, out, len(store.read(out)), len(designs)) from err
    frame = store.read(out)
    statuses = {s: int(c) for s, c in Counter(frame["status"]).items() if s in STATUSES}
    return SweepSummary(out, len(designs), evaluated, statuses, time.perf_counter() - start, monitor.most)
