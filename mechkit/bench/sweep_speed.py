"""Speed of design studies: the load path (xacro vs the template cache) and sweeps on 1 and 2 workers.

`load_times` builds a mechanism with new parameters each run (so xacro's own memo never answers),
through xacro (`mechkit.mechanism.from_params`) and through `TemplateCache` + `Mechanism`, and
reports medians. `sweep_speed` runs the same four-bar sweep on a LocalCluster of 1 and of 2 worker
processes (cluster start not timed) and reports each wall time (each worker pinned to its own CPU,
`pin_workers`) and the parallel efficiency T1 / (2 T2).
"""

from __future__ import annotations

import os
import tempfile
import time
from dataclasses import dataclass, fields
from typing import Any

import numpy as np

from mechkit.catalog.registry import get_spec
from mechkit.loading import from_expanded
from mechkit.sources.template_cache import TemplateCache
from mechkit.sources.xacro_file import render_urdf
from mechkit.sweep.engine import dask_client, sweep
from mechkit.sweep.metrics import Study
from mechkit.sweep.space import DesignSpace, parse_axis


@dataclass(frozen=True)
class LoadTime:
    """Median times (ms) of one load with new parameters: render + build + home assembly.

    Attributes:
        name: the mechanism.
        xacro_ms: through xacro.
        cache_ms: through the template cache (its one-off expansion excluded, `expand_ms`).
        render_xacro_ms, render_cache_ms: the URDF text alone, each way.
        expand_ms: the cache's one-off traced expansion and self-check of the structure.
        runs: loads timed each way.
    """

    name: str
    xacro_ms: float
    cache_ms: float
    render_xacro_ms: float
    render_cache_ms: float
    expand_ms: float
    runs: int


def _variants(name: str, runs: int):
    spec = get_spec(name)
    base = spec.params()
    floats = [f.name for f in fields(base) if isinstance(getattr(base, f.name), float)]
    # a relative change of 1e-9 per run in every float: new xacro arguments, the same design
    return spec, [base.replace(**{k: getattr(base, k) * (1 + 1e-9 * (i + 1)) for k in floats}) for i in range(runs)]


def load_times(
    names: tuple[str, ...] = ("four_bar", "ten_bar", "deployable_9rr12uru"), runs: int = 7
) -> list[LoadTime]:
    """Median load times of each mechanism with new parameters, through xacro and through the cache.

    Args:
        names: registered mechanisms.
        runs: parameter sets timed per route (each new to xacro's memo).

    Returns:
        One row per mechanism: the cache's one-off expansion, the median render and load times (s) through xacro
            and through the cache.
    """
    rows = []
    for name in names:
        spec, variants = _variants(name, 2 * runs)
        start = time.perf_counter()
        cache = TemplateCache(spec.template_path)
        cache.render(spec.params().xacro_args())
        expand = time.perf_counter() - start
        t_xacro, t_cache, r_xacro, r_cache = [], [], [], []
        for params in variants[:runs]:  # arguments never seen before: xacro's memo cannot answer
            start = time.perf_counter()
            text = render_urdf(spec.template_path, params.xacro_args())
            r_xacro.append(time.perf_counter() - start)
            from_expanded(spec, params, text)
            t_xacro.append(time.perf_counter() - start)
        for params in variants[runs:]:
            start = time.perf_counter()
            text = cache.render(params.xacro_args())
            r_cache.append(time.perf_counter() - start)
            from_expanded(spec, params, text)
            t_cache.append(time.perf_counter() - start)
        rows.append(
            LoadTime(
                name,
                1e3 * float(np.median(t_xacro)),
                1e3 * float(np.median(t_cache)),
                1e3 * float(np.median(r_xacro)),
                1e3 * float(np.median(r_cache)),
                1e3 * expand,
                runs,
            )
        )
    return rows


@dataclass(frozen=True)
class SweepSpeed:
    """One four-bar sweep timed on 1 and 2 workers.

    Attributes:
        designs: designs in the sweep; samples: instants of each design's motion study.
        seconds: {workers: wall time of the sweep (s), cluster start excluded}.
        efficiency: T1 / (2 T2).
        statuses: status counts of the sweep.
    """

    designs: int
    samples: int
    seconds: dict[int, float]
    efficiency: float
    statuses: dict[str, int]


def pin_to_cpu(cpu: int) -> None:
    """Pin every thread of this process to one CPU (Linux; threads started later inherit it).

    Args:
        cpu: the CPU's number.
    """
    for tid in os.listdir("/proc/self/task"):
        os.sched_setaffinity(int(tid), {cpu})


def pin_workers(client: Any) -> None:
    """One CPU per worker process of a Dask client's cluster, where the system can pin (Linux).

    A lone unpinned worker is slower per design than each of two (its compute and event-loop threads
    hand the GIL across cores; measured in docs/sweeps.md, "A 1,000-design sweep, and 1 vs 2 workers"):
    pinning both runs alike makes T1 / (2 T2) compare the engine, not that handicap.

    Args:
        client: a `distributed.Client`.
    """
    if not hasattr(os, "sched_setaffinity"):
        return
    cpus = sorted(os.sched_getaffinity(0))
    for i, address in enumerate(sorted(client.scheduler_info()["workers"])):
        client.run(pin_to_cpu, cpus[i % len(cpus)], workers=[address])


def sweep_speed(designs: int = 1000, samples: int = 100, seed: int = 0) -> SweepSpeed:
    """A Latin hypercube of four-bar designs (crank 0.06-0.14 m, coupler 0.24-0.32 m, rocker 0.18-0.26 m,
    ground 0.26-0.34 m), each turning its crank once over `samples` instants, on 1 then 2 workers.

    Args:
        designs: designs of the hypercube.
        samples: instants of each design's crank turn.
        seed: the hypercube's seed.

    Returns:
        The wall times (s) on 1 and 2 workers, the efficiency T1 / (2 T2), and the statuses of the designs.
    """
    space = DesignSpace(
        tuple(parse_axis(a) for a in ("crank=0.06:0.14", "coupler=0.24:0.32", "rocker=0.18:0.26", "ground=0.26:0.34")),
        "lhs",
        designs,
        seed,
    )
    study = Study(law="turn", samples=samples)
    seconds, statuses = {}, {}
    for workers in (1, 2):
        with dask_client(None, workers) as client, tempfile.TemporaryDirectory() as tmp:
            address = client.scheduler.address
            pin_workers(client)
            start = time.perf_counter()
            summary = sweep("four_bar", space, f"{tmp}/r", study, scheduler=address, workers=workers)
            seconds[workers] = time.perf_counter() - start
            statuses = summary.statuses
    return SweepSpeed(designs, samples, seconds, seconds[1] / (2 * seconds[2]), statuses)
