"""Sweeps on a real Dask cluster: `dask scheduler` and `dask worker` as separate processes on 127.0.0.1,
a sweep sent through `--scheduler`, a sweep killed with SIGKILL midway and resumed, and what the cluster
itself can do to a sweep (marked slow: they wait on real processes): its scheduler killed mid-sweep, no
worker at the start or all of them gone, a task that kills its worker, a TLS scheduler. The embedded
cluster stays private (127.0.0.1, no dashboard unless asked for)."""

from __future__ import annotations

import datetime
import ipaddress
import os
import shlex
import signal
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request
from pathlib import Path

import pytest
from tests_support import ROOT

from mechkit.cli.sweep import EXIT_NO_WORKERS, EXIT_SCHEDULER_LOST, EXIT_TASK_FAILED, EXIT_UNREACHABLE
from mechkit.sweep import read
from mechkit.sweep.cluster import dask_client
from mechkit.sweep.log_file import LOG

DASK = Path(sys.executable).parent / "dask"
FOUR_BAR = ("four_bar", "--grid", "crank=0.06:0.12", "--grid", "coupler=0.25:0.32", "--law", "turn")


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _env(**extra: str) -> dict:
    return {**os.environ, "PYTHONPATH": str(ROOT), "MECHKIT_DASK_SCHEDULER": "", **extra}


def _stop(process: subprocess.Popen, sig: int = signal.SIGTERM) -> None:
    if process.poll() is None:
        os.killpg(process.pid, sig)
        try:
            process.wait(10)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()


class Cluster:
    """A `dask scheduler` and its `dask worker`s (one thread each), each its own process group, on 127.0.0.1.

    Args:
        tls: folder holding cert.pem and key.pem: the scheduler and workers then speak TLS only.
        port: the scheduler's port (default: a free one).
        config: Dask configuration of the scheduler, as environment variables.
    """

    def __init__(self, tls: Path | None = None, port: int | None = None, config: dict | None = None) -> None:
        if not DASK.exists():
            pytest.skip("the dask command is not installed")
        self.port = port or _free_port()
        self.address = f"{'tls' if tls else 'tcp'}://127.0.0.1:{self.port}"
        self.tls = (
            [
                "--tls-ca-file",
                str(tls / "cert.pem"),
                "--tls-cert",
                str(tls / "cert.pem"),
                "--tls-key",
                str(tls / "key.pem"),
            ]
            if tls
            else []
        )
        self.workers: list[subprocess.Popen] = []
        self.scheduler = self._start(
            "scheduler",
            "--host",
            "127.0.0.1",
            "--port",
            str(self.port),
            "--protocol",
            "tls" if tls else "tcp",
            "--no-dashboard",
            "--dashboard-address",
            "127.0.0.1:0",  # its HTTP routes: loopback only
            env=_env(**(config or {})),
        )

    def _start(self, *args: str, env: dict | None = None) -> subprocess.Popen:
        return subprocess.Popen(
            [str(DASK), *args, *self.tls],
            env=env or _env(),
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            start_new_session=True,
        )

    def add_worker(self) -> subprocess.Popen:
        """Start one more worker process (with its nanny)."""
        worker = self._start(
            "worker",
            self.address,
            "--host",
            "127.0.0.1",
            "--nworkers",
            "1",
            "--nthreads",
            "1",
            "--no-dashboard",
            "--dashboard-address",
            "127.0.0.1:0",
        )
        self.workers.append(worker)
        return worker

    def wait_for_workers(self, n: int) -> None:
        """Return once `n` workers serve the scheduler (60 s at most)."""
        from distributed import Client
        from distributed.security import Security

        pem = self.tls[1::2]
        security = (
            Security(tls_ca_file=pem[0], tls_client_cert=pem[1], tls_client_key=pem[2], require_encryption=True)
            if self.tls
            else None
        )
        with Client(self.address, timeout="30s", security=security) as client:
            client.wait_for_workers(n, timeout=60)

    def stop(self) -> None:
        """Stop every process still running."""
        for process in (*self.workers, self.scheduler):
            _stop(process)


@pytest.fixture
def clusters():
    """Start clusters with `clusters(...)` (arguments of `Cluster`); every one is stopped after the test."""
    started: list[Cluster] = []

    def start(**kw) -> Cluster:
        started.append(Cluster(**kw))
        return started[-1]

    yield start
    for cluster in started:
        cluster.stop()


@pytest.fixture(scope="module")
def scheduler():
    """A scheduler and one worker (one thread), each its own process; stopped after the module."""
    cluster = Cluster()
    cluster.add_worker()
    try:
        cluster.wait_for_workers(1)
        yield cluster.address
    finally:
        cluster.stop()


def _cli(*args: str, quiet: bool = True, env: dict | None = None, **kw) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-m", "mechkit", "sweep", *args, *(["-q"] if quiet else [])],
        env=env or _env(),
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        **kw,
    )


def _run(command: list[str]) -> subprocess.CompletedProcess:
    return subprocess.run(command, env=_env(), capture_output=True, text=True, timeout=180, check=False)


def _rows(out: Path) -> int:
    """Design rows on disk (`read` refuses a design written twice)."""
    return len(read(out)) if (out / "sweep.json").exists() else 0


def _wait_for_parts(out: Path, n: int, process: subprocess.Popen, timeout: float = 90) -> None:
    parts = out / "parts"
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline and process.poll() is None:
        if parts.exists() and len(list(parts.glob("part-*.parquet"))) >= n:
            return
        time.sleep(0.05)
    raise AssertionError(f"fewer than {n} part files in {timeout} s (exit status {process.poll()})")


def _resume_command(stderr: str) -> list[str]:
    """The command the error line says resumes the sweep, as this interpreter runs it."""
    words = shlex.split(stderr.split("resume with: ", 1)[1])
    assert words[:2] == ["mechkit", "sweep"]
    return [sys.executable, "-m", "mechkit", *words[1:]]


def _one_error_line(stderr: str, notices: bool = False) -> str:
    """The error line, which ends stderr; before it only "no worker" notices, when `notices` allows them."""
    lines = stderr.strip().splitlines()
    assert "Traceback" not in stderr and lines[-1].startswith("mechkit: error: "), stderr
    assert all(n.startswith("mechkit: no worker serves ") for n in lines[:-1]) if notices else len(lines) == 1, stderr
    return lines[-1]


def test_sweep_through_scheduler(scheduler, tmp_path):
    out = tmp_path / "r"
    done = _cli(
        "four_bar",
        "--grid",
        "crank=0.06:0.2:2",
        "--grid",
        "rocker=0.2:0.3:2",
        "--law",
        "turn",
        "--samples",
        "20",
        "-o",
        str(out),
        "--scheduler",
        scheduler,
    )
    stdout, stderr = done.communicate(timeout=120)
    assert done.returncode == 0, stderr
    assert "on 1 workers" in stdout
    frame = read(out)
    assert list(frame["index"]) == list(range(4))
    assert set(frame["status"]) <= {"ok", "singular"} and (frame["status"] == "ok").any()


def test_killed_sweep_resumes_every_design_once(scheduler, tmp_path):
    out = tmp_path / "r"
    args = (
        "four_bar",
        "--lhs",
        "40",
        "--seed",
        "7",
        "--grid",
        "crank=0.06:0.12",
        "--grid",
        "coupler=0.25:0.32",
        "--law",
        "turn",
        "--samples",
        "30",
        "-o",
        str(out),
        "--scheduler",
        scheduler,
        "--chunk-size",
        "2",
    )
    first = _cli(*args, start_new_session=True)
    _wait_for_parts(out, 3, first)
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
    assert not list((out / "parts").glob(".*.tmp"))


def _listening(pids: list[int]) -> set[tuple[str, int]]:
    import psutil

    return {
        (c.laddr.ip, c.laddr.port)
        for pid in pids
        for c in psutil.Process(pid).net_connections("inet")
        if c.status == psutil.CONN_LISTEN
    }


def _http_status(url: str) -> int:
    try:
        with urllib.request.urlopen(url, timeout=10) as reply:
            return reply.status
    except urllib.error.HTTPError as err:
        return err.code


@pytest.mark.parametrize("dashboard", [False, True])
def test_embedded_cluster_stays_private(dashboard):
    """Every socket the embedded cluster listens on (scheduler, workers, nannies, HTTP) is on 127.0.0.1;
    its dashboard is served only when asked for."""
    with dask_client(None, 2, dashboard=dashboard) as client:
        info = client.scheduler_info()
        workers = client.run(os.getpid)  # the worker processes; the scheduler and nannies run in this one
        sockets = _listening([os.getpid(), *workers.values()])
        http = info["services"]["dashboard"]  # the scheduler's HTTP server (health routes, dashboard if any)
        status = _http_status(f"http://127.0.0.1:{http}/status")
        health = _http_status(f"http://127.0.0.1:{http}/health")
    print(f"\nlistening ({'with' if dashboard else 'no'} dashboard): {sorted(sockets)}; /status -> {status}")
    assert info["address"].startswith("tcp://127.0.0.1:") and len(info["workers"]) == 2
    assert all(w.startswith("tcp://127.0.0.1:") for w in info["workers"])
    assert len(sockets) >= 4 and {ip for ip, _ in sockets} == {"127.0.0.1"}
    assert ("127.0.0.1", http) in sockets and health == 200
    assert status == (200 if dashboard else 404)
    if dashboard:
        assert client.dashboard_link == f"http://127.0.0.1:{http}/status"


@pytest.mark.slow
def test_scheduler_killed_mid_sweep_then_resumed_on_a_new_cluster(clusters, tmp_path):
    """SIGKILL the scheduler mid-sweep: one line (exit status 5) with the designs saved and the command
    that resumes; a new scheduler at the same address and a new worker finish the rest, each design once."""
    first = clusters()
    first.add_worker()
    first.wait_for_workers(1)
    out = tmp_path / "r"
    sweep = _cli(
        *FOUR_BAR,
        "--lhs",
        "40",
        "--seed",
        "3",
        "--samples",
        "30",
        "--chunk-size",
        "2",
        "-o",
        str(out),
        "--scheduler",
        first.address,
    )
    _wait_for_parts(out, 3, sweep)
    os.killpg(first.scheduler.pid, signal.SIGKILL)
    killed = time.monotonic()
    _, stderr = sweep.communicate(timeout=60)
    took = time.monotonic() - killed
    before = _rows(out)
    print(f"\nscheduler killed: exit status {sweep.returncode} {took:.1f} s later, {before} of 40 designs on disk")
    line = _one_error_line(stderr)
    assert sweep.returncode == EXIT_SCHEDULER_LOST and took < 20
    assert 0 < before < 40 and f"lost mid-sweep (the connection to it closed); {before} of 40 designs are saved" in line
    assert f"--resume --scheduler {first.address}" in line
    assert "SchedulerLost" in (out / LOG).read_text()  # the details are in the log file
    first.stop()

    second = clusters(port=first.port)
    second.add_worker()
    second.wait_for_workers(1)
    resumed = _run(_resume_command(stderr))
    assert resumed.returncode == 0, resumed.stderr
    after = read(out)
    print(f"resumed on a new cluster: {after.shape[0]} of 40 designs on disk ({40 - before} evaluated now)")
    assert f"({40 - before} evaluated now)" in resumed.stdout
    assert sorted(after["index"]) == list(range(40))  # every design, exactly once


@pytest.mark.slow
def test_empty_then_vanishing_cluster(clusters, tmp_path):
    """A scheduler without a worker: a notice at once, then exit status 4 after --wait-workers; with a
    worker the sweep runs; its only worker killed mid-sweep: the same; a new worker finishes it."""
    cluster = clusters()
    out = tmp_path / "r"
    args = (
        *FOUR_BAR,
        "--lhs",
        "30",
        "--seed",
        "5",
        "--samples",
        "30",
        "--chunk-size",
        "2",
        "-o",
        str(out),
        "--scheduler",
        cluster.address,
        "--wait-workers",
        "3",
    )
    started = time.monotonic()
    empty = _cli(*args)
    notice = empty.stderr.readline()
    noticed = time.monotonic() - started
    _, rest = empty.communicate(timeout=60)
    waited = time.monotonic() - started - noticed
    print(
        f"\nno worker: notice after {noticed:.1f} s, exit status {empty.returncode} {waited:.1f} s later, "
        f"{_rows(out)} of 30 designs on disk"
    )
    assert notice.startswith(f"mechkit: no worker serves the Dask scheduler {cluster.address}; waiting up to 3 s")
    line = _one_error_line(rest)
    assert empty.returncode == EXIT_NO_WORKERS and 3 <= waited < 10
    assert "no worker served it for 3 s; 0 of 30 designs are saved" in line and _rows(out) == 0

    worker = cluster.add_worker()
    cluster.wait_for_workers(1)
    resumed = _cli(*_resume_command(line)[4:])
    _wait_for_parts(out, 3, resumed)
    _stop(worker, signal.SIGKILL)
    killed = time.monotonic()
    _, stderr = resumed.communicate(timeout=60)
    took = time.monotonic() - killed
    before = _rows(out)
    print(f"worker killed: exit status {resumed.returncode} {took:.1f} s later, {before} of 30 designs on disk")
    lines = stderr.strip().splitlines()
    assert resumed.returncode == EXIT_NO_WORKERS and 3 <= took < 15
    assert lines[0].startswith("mechkit: no worker serves") and len(lines) == 2 and "Traceback" not in stderr
    assert 0 < before < 30 and f"{before} of 30 designs are saved" in lines[1]

    cluster.add_worker()
    cluster.wait_for_workers(1)
    final = _run(_resume_command(lines[1]))
    assert final.returncode == 0, final.stderr
    after = read(out)
    print(f"a new worker: {after.shape[0]} of 30 designs on disk ({30 - before} evaluated now)")
    assert sorted(after["index"]) == list(range(30)) and f"({30 - before} evaluated now)" in final.stdout


@pytest.mark.slow
def test_task_that_kills_its_worker(clusters, tmp_path):
    """A scheduler that allows no task to outlive its worker (allowed-failures 0): the worker SIGKILLed
    mid-task fails the sweep with exit status 6 (KilledWorker), not as a design; a new worker resumes it."""
    cluster = clusters(config={"DASK_DISTRIBUTED__SCHEDULER__ALLOWED_FAILURES": "0"})
    worker = cluster.add_worker()
    cluster.wait_for_workers(1)
    out = tmp_path / "r"
    sweep = _cli(
        *FOUR_BAR,
        "--lhs",
        "30",
        "--seed",
        "9",
        "--samples",
        "30",
        "--chunk-size",
        "2",
        "-o",
        str(out),
        "--scheduler",
        cluster.address,
    )
    _wait_for_parts(out, 3, sweep)
    _stop(worker, signal.SIGKILL)
    _, stderr = sweep.communicate(timeout=60)
    before = _rows(out)
    line = _one_error_line(stderr, notices=True)  # the worker gone: "no worker" may come first
    print(f"\nworker killed mid-task: exit status {sweep.returncode}, {before} of 30 designs on disk: {line[:160]}")
    assert sweep.returncode == EXIT_TASK_FAILED and "a task failed on the cluster (KilledWorker" in line
    assert 0 < before < 30 and f"{before} of 30 designs are saved" in line

    cluster.add_worker()
    cluster.wait_for_workers(1)
    resumed = _run(_resume_command(line))
    assert resumed.returncode == 0, resumed.stderr
    after = read(out)
    print(f"a new worker: {after.shape[0]} of 30 designs on disk ({30 - before} evaluated now)")
    assert sorted(after["index"]) == list(range(30)) and f"({30 - before} evaluated now)" in resumed.stdout


@pytest.fixture
def certificate(tmp_path) -> Path:
    """A throwaway self-signed certificate (EC P-256, one day) and its key: cert.pem, key.pem."""
    from cryptography import x509
    from cryptography.hazmat.primitives import hashes, serialization
    from cryptography.hazmat.primitives.asymmetric import ec
    from cryptography.x509.oid import NameOID

    key = ec.generate_private_key(ec.SECP256R1())
    name = x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, "mechkit test cluster")])
    now = datetime.datetime.now(datetime.timezone.utc)
    cert = (
        x509.CertificateBuilder()
        .subject_name(name)
        .issuer_name(name)
        .public_key(key.public_key())
        .serial_number(x509.random_serial_number())
        .not_valid_before(now - datetime.timedelta(minutes=5))
        .not_valid_after(now + datetime.timedelta(days=1))
        .add_extension(x509.BasicConstraints(ca=True, path_length=None), critical=True)
        .add_extension(x509.SubjectAlternativeName([x509.IPAddress(ipaddress.ip_address("127.0.0.1"))]), critical=False)
        .sign(key, hashes.SHA256())
    )
    folder = tmp_path / "tls"
    folder.mkdir()
    (folder / "cert.pem").write_bytes(cert.public_bytes(serialization.Encoding.PEM))
    (folder / "key.pem").write_bytes(
        key.private_bytes(serialization.Encoding.PEM, serialization.PrivateFormat.PKCS8, serialization.NoEncryption())
    )
    return folder


@pytest.mark.slow
def test_tls_cluster(clusters, certificate, tmp_path):
    """A TLS scheduler and worker: a sweep through them with --tls-* files, another with the files named
    in Dask's configuration; a plain tcp:// client is refused (exit status 3), nothing evaluated."""
    cluster = clusters(tls=certificate)
    cluster.add_worker()
    cluster.wait_for_workers(1)
    pem = {
        "--tls-ca": certificate / "cert.pem",
        "--tls-cert": certificate / "cert.pem",
        "--tls-key": certificate / "key.pem",
    }
    out = tmp_path / "flags"
    flags = _cli(
        *FOUR_BAR,
        "--lhs",
        "8",
        "--samples",
        "20",
        "-o",
        str(out),
        "--scheduler",
        cluster.address,
        *(str(w) for item in pem.items() for w in item),
        quiet=False,
    )
    stdout, stderr = flags.communicate(timeout=120)
    assert flags.returncode == 0, stderr
    assert "on 1 workers" in stdout and "1 worker]" in stderr  # the progress line says who serves it
    assert sorted(read(out)["index"]) == list(range(8))

    out = tmp_path / "config"
    config = {
        "DASK_DISTRIBUTED__COMM__TLS__CA_FILE": str(pem["--tls-ca"]),
        "DASK_DISTRIBUTED__COMM__TLS__CLIENT__CERT": str(pem["--tls-cert"]),
        "DASK_DISTRIBUTED__COMM__TLS__CLIENT__KEY": str(pem["--tls-key"]),
    }
    configured = _cli(
        *FOUR_BAR, "--lhs", "8", "--samples", "20", "-o", str(out), "--scheduler", cluster.address, env=_env(**config)
    )
    _, stderr = configured.communicate(timeout=120)
    assert configured.returncode == 0, stderr
    assert sorted(read(out)["index"]) == list(range(8))

    out = tmp_path / "plain"
    plain = _cli(
        *FOUR_BAR,
        "--lhs",
        "8",
        "--samples",
        "20",
        "-o",
        str(out),
        "--scheduler",
        cluster.address.replace("tls://", "tcp://"),
    )
    _, stderr = plain.communicate(timeout=120)
    line = _one_error_line(stderr)
    print(f"\ntcp:// client to the TLS scheduler: exit status {plain.returncode}: {line}")
    assert plain.returncode == EXIT_UNREACHABLE and "cannot connect" in line and _rows(out) == 0
