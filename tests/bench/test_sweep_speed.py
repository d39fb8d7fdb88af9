"""The sweep benchmark on a real embedded Dask cluster: each worker pinned to its own CPU (every thread
of it), and a tiny 1 vs 2 worker sweep that returns its figures."""

from __future__ import annotations

import os

import pytest

from mechkit.bench.sweep_speed import pin_workers, sweep_speed
from mechkit.sweep.engine import dask_client

pytestmark = pytest.mark.skipif(not hasattr(os, "sched_setaffinity"), reason="CPU pinning needs Linux")


def _thread_affinities() -> list[list[int]]:
    return [sorted(os.sched_getaffinity(int(tid))) for tid in os.listdir("/proc/self/task")]


def test_each_worker_gets_its_own_cpu():
    cpus = sorted(os.sched_getaffinity(0))
    with dask_client(None, 2) as client:
        pin_workers(client)
        per_worker = client.run(_thread_affinities)
    pinned = [{tuple(a) for a in threads} for threads in per_worker.values()]
    assert all(len(p) == 1 and len(next(iter(p))) == 1 for p in pinned), pinned  # every thread, one CPU
    used = sorted(next(iter(p))[0] for p in pinned)
    assert used == (cpus[:2] if len(cpus) >= 2 else cpus * 2)


def test_tiny_sweep_speed_reports_both_runs():
    s = sweep_speed(designs=6, samples=5)
    assert set(s.seconds) == {1, 2} and all(t > 0 for t in s.seconds.values())
    assert abs(s.efficiency - s.seconds[1] / (2 * s.seconds[2])) < 1e-12
    assert sum(s.statuses.values()) == 6
