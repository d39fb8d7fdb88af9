"""A live meshcat viewer: a meshcat server on this machine (127.0.0.1) showing a mechanism at a pose, or
playing one of its scenes, in any browser that opens its address, for as long as it runs.

The server is meshcat's own (its web page and websocket bridge, `meshcat.servers.zmqserver`), started
in a child process bound to the loopback address only; the drawing is the one of the static pages
(`mechkit.viz.pages.compose`: same parts, colours, framing and animation), sent to the server command
by command, which replays the whole scene to every browser that connects later. A scene plays in the
browser, ping-pong, forever. Nothing here prints; `mechkit view` is the command.
"""

from __future__ import annotations

import os
import re
import select
import subprocess
import sys
import time
from html import escape
from typing import Self

import numpy as np

from mechkit.base.exceptions import ExternalToolFailed, InvalidParameters, MechkitError, MethodUnavailable
from mechkit.mechanism import Mechanism
from mechkit.scenes import scene_poses
from mechkit.viz.meshcat_page import StaticScene
from mechkit.viz.meshes import MeshSearch
from mechkit.viz.pages import compose

HOST = "127.0.0.1"
START_TIMEOUT = 30.0  # s for the server to say where it listens
REPLY_TIMEOUT_MS = 10000  # ms for the server to acknowledge one command
# meshcat's server, with its web server bound to the loopback address (it listens on every address else);
# on Linux it gets SIGTERM when the process that started it dies, however that dies (PR_SET_PDEATHSIG)
_SERVER = f"""
import ctypes, signal, sys, tornado.web
if sys.platform.startswith("linux"):
    ctypes.CDLL(None).prctl(1, signal.SIGTERM)
from meshcat.servers import zmqserver
listen = tornado.web.Application.listen
tornado.web.Application.listen = lambda self, port, **kw: listen(self, port, address={HOST!r}, **kw)
sys.argv = ["meshcat-server"]
zmqserver.main()
"""


class LiveScene(StaticScene):
    """A `StaticScene` whose commands go to a running meshcat server (a zmq REQ socket) as they are made."""

    def __init__(self, socket) -> None:
        super().__init__()
        self._socket = socket

    def _send(self, lowered: dict) -> None:
        self._socket.send_multipart([lowered["type"].encode(), lowered["path"].encode(), self._umsgpack.packb(lowered)])
        reply = self._socket.recv()
        if reply != b"ok":
            raise ExternalToolFailed(
                "the meshcat server", f"refused {lowered['type']!r}: {reply.decode(errors='replace')}"
            )


class LiveViewer:
    """A meshcat server in a child process, and what it shows.

    Use as a context manager, or call `close()`: the server ends with it (and with this process).

    Attributes:
        url: the viewer's web address (http://127.0.0.1:PORT/static/).

    Raises:
        MethodUnavailable: meshcat is not installed.
        ExternalToolFailed: its server did not start within START_TIMEOUT.
    """

    def __init__(self) -> None:
        try:
            import zmq
        except ImportError:
            raise MethodUnavailable("the live viewer", "meshcat is not installed: pip install 'mechkit[viz]'") from None
        self._process = subprocess.Popen(
            [sys.executable, "-u", "-c", _SERVER],
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            stdin=subprocess.DEVNULL,
            start_new_session=True,
        )
        try:
            zmq_url, self.url = self._addresses()
        except MechkitError:
            self.close()
            raise
        self._shown = 0  # how many drawings were shown (the current one is under /mechanism<_shown>)
        self._context = zmq.Context()
        self._socket = self._context.socket(zmq.REQ)
        self._socket.setsockopt(zmq.RCVTIMEO, REPLY_TIMEOUT_MS)
        self._socket.setsockopt(zmq.LINGER, 0)
        self._socket.connect(zmq_url)

    def _addresses(self) -> tuple[str, str]:
        """(zmq address, web address) the server prints when it listens."""
        deadline, out = time.monotonic() + START_TIMEOUT, b""
        fd = self._process.stdout.fileno()
        while (left := deadline - time.monotonic()) > 0:
            if select.select([fd], [], [], left)[0]:
                chunk = os.read(fd, 4096)
                if not chunk:  # the server ended
                    raise ExternalToolFailed(
                        "the meshcat server", f"exited with {self._process.wait()} before listening"
                    )
                out += chunk
                text = out.decode(errors="replace")
                found = [re.search(rf"^{key}=(\S+)$", text, re.MULTILINE) for key in ("zmq_url", "web_url")]
                if all(found):
                    return found[0].group(1), found[1].group(1)
        raise ExternalToolFailed("the meshcat server", f"did not start within {START_TIMEOUT:.0f} s")

    def show(
        self,
        mechanism: Mechanism,
        q: np.ndarray | None = None,
        scene: str | None = None,
        meshes: MeshSearch | None = None,
    ) -> None:
        """Show the mechanism at q (default: its home assembly), or play one of its scenes; replaces
        whatever was shown.

        Args:
            mechanism: the mechanism.
            q: a configuration (size nq), assembled.
            scene: a scene name (`mechkit.scenes.scenes`), played ping-pong in the browser.
            meshes: where mesh files are looked for.

        Raises:
            InvalidParameters: both q and scene, or an unknown scene.
            ExternalToolFailed: the server stopped answering.
        """
        if q is not None and scene is not None:
            raise InvalidParameters("q", "given", "give either q (one pose) or scene (an animation), not both")
        poses = (
            scene_poses(mechanism, scene)
            if scene is not None
            else [mechanism.home_q if q is None else np.asarray(q, dtype=float)]
        )
        live = LiveScene(self._socket)
        try:
            if self._shown:
                live._send(live._commands_module.Delete(live._path(f"/mechanism{self._shown}")).lower())
            # a new root each time: the tracks of a scene shown before keep playing, but on nothing
            self._shown += 1
            compose(live, mechanism, poses, animate=scene is not None, meshes=meshes, root=f"/mechanism{self._shown}")
        except Exception as err:  # zmq.Again: no reply within REPLY_TIMEOUT_MS
            if isinstance(err, MechkitError):
                raise
            raise ExternalToolFailed(
                f"the meshcat server at {self.url}", f"did not answer ({type(err).__name__})"
            ) from None

    @property
    def running(self) -> bool:
        """Whether the server process is still running."""
        return self._process.poll() is None

    def close(self) -> None:
        """Stop the server (its page stops updating) and release the socket."""
        if getattr(self, "_socket", None) is not None:
            self._context.destroy(linger=0)  # every socket closed without waiting: term() alone can block
            self._socket = None
        if self._process.poll() is None:
            self._process.terminate()
            try:
                self._process.wait(timeout=5)
            except subprocess.TimeoutExpired:
                self._process.kill()
                self._process.wait()
        self._process.stdout.close()

    def __enter__(self) -> Self:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def _repr_html_(self) -> str:
        """In Jupyter: the live viewer's page in a frame."""
        return (
            f'<iframe src="{escape(self.url)}" style="width: 100%; height: 420px; border: 0" '
            f'title="mechkit live viewer"></iframe>'
        )


def view(
    mechanism: Mechanism, q: np.ndarray | None = None, scene: str | None = None, meshes: MeshSearch | None = None
) -> LiveViewer:
    """Start a live viewer showing the mechanism (see `LiveViewer.show`); close it when done.

    Args:
        mechanism: the mechanism.
        q: a configuration (nq,), assembled.
        scene: a scene name, played ping-pong.
        meshes: where mesh files are looked for.

    Returns:
        The running viewer.

    Raises:
        MethodUnavailable: meshcat is not installed.
        ExternalToolFailed: its server did not start, or stopped answering.
        InvalidParameters: both q and scene, or an unknown scene.
    """
    viewer = LiveViewer()
    try:
        viewer.show(mechanism, q, scene, meshes)
    except BaseException:
        viewer.close()
        raise
    return viewer
