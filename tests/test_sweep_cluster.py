"""Sweeps on a real Dask cluster: `dask scheduler` and `dask worker` as separate processes on
127.0.0.1, a sweep sent through `--scheduler`, and a sweep killed with SIGKILL midway and resumed."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest

from mechkit.sweep import read

ROOT = Path(__file__).resolve().parent.parent
DASK = Path(sys.executable).parent / "dask"


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _env() -> dict:
    return {**os.environ, "PYTHONPATH": str(ROOT), "MECHKIT_DASK_SCHEDULER": ""}


def _stop(process: subprocess.Popen) -> None:
    if process.poll() is None:
        os.killpg(process.pid, signal.SIGTERM)
        try:
            process.wait(10)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()


@pytest.fixture(scope="module")
def scheduler():
    """A scheduler and one worker (one thread), each its own process; stopped after the module."""
    if not DASK.exists():
        pytest.skip("the dask command is not installed")
    address = f"tcp://127.0.0.1:{_free_port()}"
    port = address.rsplit(":", 1)[1]
    common = {"env": _env(), "stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL, "start_new_session": True}
    sched = subprocess.Popen([str(DASK), "scheduler", "--host", "127.0.0.1", "--port", port, "--no-dashboard"],
                             **common)
    worker = subprocess.Popen([str(DASK), "worker", address, "--host", "127.0.0.1", "--nworkers", "1",
                               "--nthreads", "1", "--no-dashboard"], **common)
    try:
        from distributed import Client

        with Client(address, timeout="30s") as client:
            client.wait_for_workers(1, timeout=60)
        yield address
    finally:
        _stop(worker)
        _stop(sched)


def _cli(*args: str, **kw) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-m", "mechkit", "sweep", *args, "-q"], env=_env(),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kw)


def test_sweep_through_scheduler(scheduler, tmp_path):
    out = tmp_path / "r"
    done = _cli("four_bar", "--grid", "crank=0.06:0.2:2", "--grid", "rocker=0.2:0.3:2", "--law", "turn",
                "--samples", "20", "-o", str(out), "--scheduler", scheduler)
    stdout, stderr = done.communicate(timeout=120)
    assert done.returncode == 0, stderr
    assert "on 1 workers" in stdout
    frame = read(out)
    assert list(frame["index"]) == list(range(4))
    assert set(frame["status"]) <= {"ok", "singular"} and (frame["status"] == "ok").any()


def test_killed_sweep_resumes_every_design_once(scheduler, tmp_path):
    out = tmp_path / "r"
    args = ("four_bar", "--lhs", "40", "--seed", "7", "--grid", "crank=0.06:0.12", "--grid", "coupler=0.25:0.32",
            "--law", "turn", "--samples", "30", "-o", str(out), "--scheduler", scheduler, "--chunk-size", "2")
    first = _cli(*args, start_new_session=True)
    parts = out / "parts"
    deadline = time.monotonic() + 90
    while time.monotonic() < deadline and len(list(parts.glob("part-*.parquet")) if parts.exists() else []) < 3:
        time.sleep(0.05)
    os.killpg(first.pid, signal.SIGKILL)
    first.communicate()
    before = len(read(out))
    assert 0 < before < 40, "the sweep must be killed midway"
    again = _cli(*args, "--resume")
    stdout, stderr = again.communicate(timeout=180)
    assert again.returncode == 0, stderr
    assert f"({40 - before} evaluated now)" in stdout
    frame = read(out)
    assert sorted(frame["index"]) == list(range(40))  # every design, exactly once
    assert not list(parts.glob(".*.tmp"))
