"""The sweep engine: designs in chunks, one Dask task per chunk, rows written as chunks finish.

With no scheduler address (argument or `MECHKIT_DASK_SCHEDULER`), an embedded `LocalCluster` of
worker processes (one thread each) on 127.0.0.1 starts and stops with the sweep; with one, the same
tasks go to that running cluster. The client writes each finished chunk's part file (`store`), so
a sweep killed at any moment resumes with `resume=True`.
"""

from __future__ import annotations

import logging
import math
import os
import time
from collections import Counter
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import asdict, dataclass, fields
from pathlib import Path

from mechkit.base.exceptions import InvalidParameters, MethodUnavailable
from mechkit.catalog.registry import get_spec
from mechkit.loading import load
from mechkit.sweep import store
from mechkit.sweep.evaluate import STATUSES, Chunk, evaluate_chunk
from mechkit.sweep.metrics import Study
from mechkit.sweep.space import DesignSpace
from mechkit.sweep.specific import resolve

SCHEDULER_ENV = "MECHKIT_DASK_SCHEDULER"


@dataclass(frozen=True)
class SweepSummary:
    """What a sweep run did.

    Attributes:
        out: the results folder.
        designs: designs in the sweep.
        evaluated: designs evaluated by this run (the rest were done by an earlier, resumed run).
        statuses: status -> number of rows in the whole dataset after this run.
        seconds: wall time of this run (s), cluster start included.
        workers: Dask workers that served the run.
    """

    out: Path
    designs: int
    evaluated: int
    statuses: dict[str, int]
    seconds: float
    workers: int


@contextmanager
def dask_client(scheduler: str | None = None, workers: int | None = None) -> Iterator:
    """A Dask client: to `scheduler` (or `$MECHKIT_DASK_SCHEDULER`), else to an embedded LocalCluster.

    Raises:
        MethodUnavailable: the scheduler cannot be reached.
    """
    from distributed import Client, LocalCluster

    address = scheduler or os.environ.get(SCHEDULER_ENV)
    if address:
        try:
            client = Client(address, timeout="15s")
        except (OSError, TimeoutError) as err:
            raise MethodUnavailable("dask scheduler", f"cannot reach {address!r}: {err}") from None
        with client:
            yield client
        return
    n = workers or os.cpu_count() or 1
    # no dashboard; the scheduler's HTTP routes on a free local port (its default 8787 may be taken)
    quiet = {"dashboard": False, "dashboard_address": "127.0.0.1:0"}
    with LocalCluster(n_workers=n, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None,
                      scheduler_kwargs=quiet, silence_logs=logging.ERROR) as cluster, Client(cluster) as client:
        yield client


def _check_axes(mechanism: str, space: DesignSpace, base: dict) -> None:
    known = {f.name: f for f in fields(get_spec(mechanism).params)}
    for name in space.names:
        if name not in known or isinstance(known[name].default, (bool, str)):
            numeric = [n for n, f in known.items() if not isinstance(f.default, (bool, str))]
            raise InvalidParameters("grid", name, f"not a numeric parameter of {mechanism}; they are {', '.join(numeric)}")
        if name in base:
            raise InvalidParameters("set", name, "is swept: it cannot also be fixed")


def sweep(mechanism: str, space: DesignSpace, out: str | Path, study: Study | None = None,
          metrics: tuple[str, ...] | None = None, *, base: dict | None = None, resume: bool = False,
          scheduler: str | None = None, workers: int | None = None, chunk_size: int | None = None,
          fast: bool = True, progress: Callable[[int], None] | None = None) -> SweepSummary:
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
            embedded LocalCluster of `workers` processes, default the CPU count).
        chunk_size: designs per task (default: about 4 tasks per worker, at most 50 designs).
        fast: build designs through the template cache (False: xacro for each design).
        progress: called with the number of designs finished, chunk by chunk.
    """
    start = time.perf_counter()
    study, base = study or Study(), dict(base or {})
    _check_axes(mechanism, space, base)
    chosen = resolve(mechanism, metrics)
    reference = load(mechanism, **base)
    columns = tuple(c for m in chosen for c in m.columns(reference))
    designs = space.designs()
    n_workers = workers or os.cpu_count() or 1
    size = chunk_size or max(1, min(50, math.ceil(len(designs) / (4 * n_workers))))
    if size < 1:
        raise InvalidParameters("chunk_size", size, "must be >= 1")
    manifest = {"mechanism": mechanism, "base": {k: str(v) for k, v in base.items()}, "space": space.to_dict(),
                "study": asdict(study), "metrics": [m.name for m in chosen], "columns": list(columns),
                "chunk_size": size, "designs": len(designs)}
    out = Path(out)
    done = store.prepare(out, manifest, designs, resume)
    row_schema = store.schema(space.names, columns)
    chunks = range(math.ceil(len(designs) / size))
    pending = [k for k in chunks if k not in done]
    evaluated = 0
    if progress is not None and done:
        progress(sum(len(range(k * size, min((k + 1) * size, len(designs)))) for k in done))
    with dask_client(scheduler, workers) as client:
        from distributed import as_completed

        served = len(client.scheduler_info()["workers"])
        futures = {}
        for k in pending:
            idx = tuple(range(k * size, min((k + 1) * size, len(designs))))
            task = Chunk(mechanism, base, space.names, idx, designs[list(idx)], study,
                         tuple(m.name for m in chosen), columns, fast)
            futures[client.submit(evaluate_chunk, task, pure=False)] = k
        for future in as_completed(futures):
            rows = future.result()
            store.write_part(out, futures[future], rows, row_schema)
            evaluated += len(rows)
            if progress is not None:
                progress(len(rows))
    frame = store.read(out)
    statuses = {s: int(c) for s, c in Counter(frame["status"]).items() if s in STATUSES}
    return SweepSummary(out, len(designs), evaluated, statuses, time.perf_counter() - start, served)
