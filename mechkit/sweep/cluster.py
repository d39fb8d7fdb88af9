"""Where a sweep's tasks run: the Dask client, its workers, a lost scheduler, TLS.

- `dask_client`: a client to a running scheduler (`tls://` addresses use the certificates of Dask's
  configuration, `distributed.comm.tls.*`; `tls_config` turns explicit files into that configuration),
  or to an embedded `LocalCluster` that stays private: every socket on 127.0.0.1, no dashboard unless
  asked for (then on 127.0.0.1 too).
- `Monitor`: yields the tasks' results as they finish while watching the cluster: the number of
  workers serving it (reported to a callback whenever it changes), a cluster without a worker for
  longer than the allowed wait (`NoWorkers`), the scheduler's connection lost (`SchedulerLost`), a
  task that failed on the cluster rather than in a design (`TaskFailed`).
"""

from __future__ import annotations

import logging
import math
import os
import queue
import time
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from mechkit.base.exceptions import InvalidArgument, MechkitError, MethodUnavailable

if TYPE_CHECKING:
    from distributed import Client, Future

#: The environment variable naming the scheduler when no address is given.
SCHEDULER_ENV = "MECHKIT_DASK_SCHEDULER"
#: Default of how long (s) a sweep waits for a worker when its cluster has none.
WAIT_WORKERS = 60.0
#: Seconds allowed to reach a scheduler.
CONNECT_TIMEOUT = 15.0
#: Seconds between two looks at the cluster (workers, connection) while tasks run.
POLL = 0.5
#: The dashboard's port on 127.0.0.1 when asked for (Dask's default; a free port if it is taken).
DASHBOARD_PORT = 8787
_TLS_KEYS = {
    "tls_ca": "distributed.comm.tls.ca-file",
    "tls_cert": "distributed.comm.tls.client.cert",
    "tls_key": "distributed.comm.tls.client.key",
}
_LOST = "lost mid-sweep (the connection to it closed)"


class ClusterError(MechkitError):
    """The Dask cluster could not serve the sweep (its designs are not at fault).

    Attributes:
        address: the scheduler's address.
        why: what happened, in words.
    """

    def __init__(self, address: str, why: str):
        self.address, self.why = address, why
        super().__init__(f"Dask scheduler {address}: {why}")


class SchedulerUnreachable(ClusterError):
    """No connection to the scheduler could be made (down, wrong address, or it refused the client)."""


class SchedulerLost(ClusterError):
    """The connection to the scheduler closed while the sweep ran (the scheduler died or was stopped)."""


class NoWorkers(ClusterError):
    """The scheduler had no worker for longer than the allowed wait.

    Attributes:
        seconds: the wait allowed (s).
    """

    def __init__(self, address: str, seconds: float):
        self.seconds = seconds
        super().__init__(address, f"no worker served it for {seconds:g} s")


class TaskFailed(ClusterError):
    """A task failed on the cluster itself (its workers died running it, or it could not run there);
    a design that fails is a row, never this."""


@dataclass(frozen=True)
class ClusterState:
    """What serves a sweep: reported when it starts and whenever the number of workers changes.

    Attributes:
        address: the scheduler's address.
        workers: workers serving it now (0: none; the sweep waits for one, up to its allowed wait).
        dashboard: the address of the embedded cluster's dashboard, or None when it has none.
    """

    address: str
    workers: int
    dashboard: str | None


def scheduler_address(scheduler: str | None = None) -> str | None:
    """The scheduler a sweep uses: `scheduler`, else `$MECHKIT_DASK_SCHEDULER`, else None (embedded).

    Args:
        scheduler: an address given explicitly.

    Returns:
        The address, or None for the embedded cluster.
    """
    return scheduler or os.environ.get(SCHEDULER_ENV) or None


def tls_config(
    address: str | None, tls_ca: str | None = None, tls_cert: str | None = None, tls_key: str | None = None
) -> dict[str, str]:
    """Dask configuration entries naming a client's TLS files (for `dask.config.set`).

    Args:
        address: the scheduler's address (the files are only for a `tls://` one).
        tls_ca: PEM file of the cluster's certificate authority.
        tls_cert: PEM file of the client's certificate (may hold the key too).
        tls_key: PEM file of the client's private key.

    Returns:
        Configuration key -> path, for the files given (empty when none is).

    Raises:
        InvalidArgument: a file is given without a `tls://` address, or is not a file.
    """
    given = {
        name: path
        for name, path in (("tls_ca", tls_ca), ("tls_cert", tls_cert), ("tls_key", tls_key))
        if path is not None
    }
    for name, path in given.items():
        if not (address or "").startswith("tls://"):
            raise InvalidArgument(
                name,
                path,
                "a TLS file is for a tls:// scheduler address; this sweep's is "
                f"{address or 'none (the embedded cluster)'}",
            )
        if not Path(path).is_file():
            raise InvalidArgument(name, path, "no such file")
    return {_TLS_KEYS[name]: str(Path(path).resolve()) for name, path in given.items()}


def check_options(
    scheduler: str | None = None, *, dashboard: bool = False, wait_workers: float = WAIT_WORKERS
) -> str | None:
    """Check a cluster's options before any work is done.

    Args:
        scheduler: the scheduler's address, or None (see `scheduler_address`).
        dashboard: whether the embedded cluster is to serve a dashboard.
        wait_workers: how long (s) a cluster may have no worker.

    Returns:
        The scheduler's address, or None for the embedded cluster.

    Raises:
        InvalidArgument: `wait_workers` negative or not finite; `dashboard` with a running scheduler;
            a `tls://` address without a CA file and client certificate in Dask's configuration.
        MethodUnavailable: `dashboard` without bokeh installed.
    """
    from distributed.security import Security

    _check_wait(wait_workers)
    address = scheduler_address(scheduler)
    if address and dashboard:
        raise InvalidArgument(
            "dashboard",
            dashboard,
            "is for the embedded cluster; a running scheduler serves its own (dask scheduler --dashboard-address)",
        )
    if dashboard:
        try:
            import bokeh  # noqa: F401 - Dask's dashboard is drawn with bokeh
        except ImportError:
            raise MethodUnavailable("dashboard", "needs bokeh: pip install -e '.[sweep]'") from None
    security = Security()
    if address and address.startswith("tls://") and not (security.tls_ca_file and security.tls_client_cert):
        raise InvalidArgument(
            "scheduler",
            address,
            "a tls:// address needs the cluster's CA file and a client "
            "certificate: --tls-ca, --tls-cert (--tls-key), or Dask's configuration "
            "distributed.comm.tls.ca-file, distributed.comm.tls.client.cert (.key)",
        )
    return address


@contextmanager
def dask_client(
    scheduler: str | None = None, workers: int | None = None, *, dashboard: bool = False
) -> Iterator[Client]:
    """A Dask client: to a running scheduler, else to an embedded LocalCluster.

    Args:
        scheduler: the scheduler's address (default: `$MECHKIT_DASK_SCHEDULER`, else the embedded
            cluster). A `tls://` address uses the certificates of Dask's configuration.
        workers: worker processes of the embedded cluster (one thread each; default the CPU count).
        dashboard: the embedded cluster serves Dask's dashboard on 127.0.0.1 (`DASHBOARD_PORT`, or a
            free port when it is taken); without it the embedded cluster has none.

    Returns:
        A context manager giving the client; leaving it closes the client (and the embedded cluster).

    Raises:
        InvalidArgument: see `check_options`.
        MethodUnavailable: `dashboard` without bokeh installed.
        SchedulerUnreachable: no connection to the scheduler within `CONNECT_TIMEOUT` seconds.
    """
    from distributed import Client, LocalCluster

    address = check_options(scheduler, dashboard=dashboard)
    if address:
        try:
            client = Client(address, timeout=f"{CONNECT_TIMEOUT}s")
        except (OSError, TimeoutError) as err:
            raise SchedulerUnreachable(address, f"cannot connect ({_text(err)})") from None
        with client:
            yield client
        return
    # no dashboard: the scheduler's HTTP routes (health, metrics) on a free port of 127.0.0.1 only
    http = {"dashboard": dashboard, "dashboard_address": f"127.0.0.1:{DASHBOARD_PORT if dashboard else 0}"}
    with (
        LocalCluster(
            n_workers=workers or os.cpu_count() or 1,
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            dashboard_address=None,
            scheduler_kwargs=http,
            silence_logs=logging.ERROR,
        ) as cluster,
        Client(cluster) as client,
    ):
        yield client


def _check_wait(wait_workers: float) -> None:
    """Refuse a wait for workers that is negative or not finite."""
    if not (math.isfinite(wait_workers) and wait_workers >= 0):
        raise InvalidArgument("wait_workers", wait_workers, "must be a finite number of seconds >= 0")


def _text(err: BaseException) -> str:
    """An exception as one line: its type and message."""
    return f"{type(err).__name__}: {' '.join(str(err).split())}"


class Monitor:
    """Watches the cluster that serves a client while its tasks run.

    Args:
        client: the connected client.
        wait_workers: how long (s) the cluster may have no worker before `NoWorkers`.
        watch: called with a `ClusterState` at the first look and whenever the number of workers changes.
        dashboard: the address of the dashboard to report in the `ClusterState` (None: none).

    Raises:
        InvalidArgument: `wait_workers` is negative or not finite.
    """

    def __init__(
        self,
        client: Client,
        wait_workers: float = WAIT_WORKERS,
        watch: Callable[[ClusterState], None] | None = None,
        dashboard: str | None = None,
    ) -> None:
        _check_wait(wait_workers)
        self.client, self.wait_workers, self.watch, self.dashboard = client, wait_workers, watch, dashboard
        self.address = client.scheduler.address
        self.most = 0  # the most workers seen serving at once
        self._workers: int | None = None
        self._none_since: float | None = None

    def look(self) -> int:
        """Look at the cluster once: the workers serving it now.

        Returns:
            The number of workers.

        Raises:
            SchedulerLost: the connection to the scheduler is closed.
            NoWorkers: no worker has served it for `wait_workers` seconds.
        """
        if self.client.status != "running":
            raise SchedulerLost(self.address, _LOST)
        try:
            workers = len(self.client.nthreads())
        except OSError as err:  # the scheduler went away during the call
            raise SchedulerLost(self.address, _LOST) from err
        if workers != self._workers:
            self._workers, self.most = workers, max(self.most, workers)
            if self.watch is not None:
                self.watch(ClusterState(self.address, workers, self.dashboard))
        now = time.monotonic()
        if workers:
            self._none_since = None
        elif self._none_since is None:
            self._none_since = now
        if self._none_since is not None and now - self._none_since >= self.wait_workers:
            raise NoWorkers(self.address, self.wait_workers)
        return workers

    def results(self, futures: Iterable[Future]) -> Iterator[tuple[Future, Any]]:
        """The futures' results as their tasks finish, looking at the cluster at least every `POLL` seconds
        meanwhile (also while a result is fetched: a result lost with its worker is computed again).

        Args:
            futures: submitted futures.

        Returns:
            An iterator of (future, its result), in the order the tasks finish.

        Raises:
            SchedulerLost: the connection to the scheduler closed (the unfinished tasks are gone).
            NoWorkers: no worker served the cluster for `wait_workers` seconds.
            TaskFailed: a task failed on the cluster (not a design: those are rows).
        """
        from distributed import CancelledError, TimeoutError

        futures = list(futures)
        if not futures:
            return
        done: queue.SimpleQueue = queue.SimpleQueue()
        for future in futures:
            future.add_done_callback(done.put)
        self.look()
        next_look = time.monotonic() + POLL
        for _ in futures:
            future = None
            while future is None:
                try:
                    future = done.get(timeout=max(0.0, next_look - time.monotonic()))
                except queue.Empty:
                    pass
                if time.monotonic() >= next_look:
                    self.look()
                    next_look = time.monotonic() + POLL
            while True:
                try:
                    result = future.result(timeout=POLL)
                    break
                except TimeoutError:  # its result went with its worker: the task runs again
                    self.look()
                except CancelledError as err:  # the client cancels every task when the connection closes
                    raise SchedulerLost(self.address, _LOST) from err
                except Exception as err:  # a design's failure is a row: this one is the cluster's
                    self.look()  # the scheduler lost mid-fetch?
                    raise TaskFailed(self.address, f"a task failed on the cluster ({_text(err)})") from err
            yield future, result
