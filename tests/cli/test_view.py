"""`mechkit view`: the live viewer in a real browser, ended by Ctrl-C (skipped where Chromium is absent)."""

from __future__ import annotations

import itertools
import os
import signal
import subprocess
import sys
import time
import urllib.error
import urllib.request

import numpy as np
import pytest
from tests_support import ROOT
from viz.in_browser import CONTROLS, assert_framed, drawn_pixels, needs_browser

from mechkit.viz.browser import screenshot

#: How long a step may take on a busy machine before the test says what it was waiting for (s, ours: the
#: default run passes with both cores of a two-core machine busy, README "Development").
READY_WITHIN = 120.0


def _frames_until_it_plays(url: str, folder) -> list[np.ndarray]:
    """Screenshots of the served page until one shows the mechanism and a later one a different moment (the
    scene plays: its frames come over the server's websocket in wall-clock time, so on a busy machine the
    first pictures may show nothing yet, or the same moment twice); each drawn picture's mask. Fails, saying
    what it waited for, after `READY_WITHIN` seconds."""
    deadline, masks, last = time.monotonic() + READY_WITHIN, [], "no picture yet"
    for k in itertools.count():
        png = screenshot(url, folder / f"frame{k}.png", budget_ms=500 if k == 0 else 3000)
        try:
            masks.append(drawn_pixels(png))
        except AssertionError as err:  # not drawn yet
            last = f"the page showed no mechanism yet ({err})"
        else:
            if len(masks) > 1 and np.mean(masks[0][CONTROLS:] != masks[-1][CONTROLS:]) > 0.002:
                return [masks[0], masks[-1]]
            last = f"{len(masks)} picture(s) of one moment"
        if time.monotonic() > deadline:
            pytest.fail(f"the live viewer at {url} did not play within {READY_WITHIN:.0f} s: {last}")
    raise AssertionError("unreachable")


@needs_browser
def test_live_viewer_in_a_real_browser_and_ctrl_c(tmp_path):
    """`mechkit view five_bar --scene sweep`: the served page shows the mechanism framed, two moments of
    the scene differ (it plays), and Ctrl-C ends the command and its server without a traceback."""
    env = dict(os.environ, PYTHONPATH=str(ROOT), PYTHONFAULTHANDLER="1")  # SIGABRT dumps where it stands
    # A test suite run as a background job (nohup ... &, some CI runners) has SIGINT ignored, its children
    # inherit that, and Python then never raises KeyboardInterrupt: the child gets Ctrl-C as a terminal sends it.
    inherited = signal.signal(signal.SIGINT, signal.default_int_handler)
    command = subprocess.Popen(
        [sys.executable, "-m", "mechkit", "view", "five_bar", "--scene", "sweep"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
    )
    signal.signal(signal.SIGINT, inherited)
    try:
        line = command.stdout.readline()
        assert "http://127.0.0.1:" in line, line + command.stderr.read()
        url = line.split(" at ", 1)[1].split()[0]
        masks = _frames_until_it_plays(url, tmp_path)
        for mask in masks:
            assert_framed(mask)
        assert np.mean(masks[0][CONTROLS:] != masks[-1][CONTROLS:]) > 0.002  # the scene plays
        command.send_signal(signal.SIGINT)
        try:
            out, err = command.communicate(timeout=READY_WITHIN)
        except subprocess.TimeoutExpired:
            command.send_signal(signal.SIGABRT)  # the fault handler prints every thread's stack, then it ends
            out, err = command.communicate()
            pytest.fail(f"mechkit view did not end within {READY_WITHIN:.0f} s of Ctrl-C; it printed {out!r}, {err!r}")
    finally:
        if command.poll() is None:
            command.kill()
            command.wait()
    assert command.returncode == 0
    assert "Traceback" not in err and out.strip().endswith("stopped")
    with pytest.raises(urllib.error.URLError):  # its server is gone with it
        urllib.request.urlopen(url, timeout=5)
