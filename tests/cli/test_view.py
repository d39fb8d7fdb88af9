"""`mechkit view`: the live viewer in a real browser, ended by Ctrl-C (skipped where Chromium is absent)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import urllib.error
import urllib.request

import numpy as np
import pytest
from tests_support import ROOT
from viz.in_browser import CONTROLS, assert_framed, drawn_pixels, needs_browser

from mechkit.viz.browser import screenshot


@needs_browser
def test_live_viewer_in_a_real_browser_and_ctrl_c(tmp_path):
    """`mechkit view five_bar --scene sweep`: the served page shows the mechanism framed, two moments of
    the scene differ (it plays), and Ctrl-C ends the command and its server without a traceback."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    command = subprocess.Popen(
        [sys.executable, "-m", "mechkit", "view", "five_bar", "--scene", "sweep"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
    )
    try:
        line = command.stdout.readline()
        assert "http://127.0.0.1:" in line, line + command.stderr.read()
        url = line.split(" at ", 1)[1].split()[0]
        early = screenshot(url, tmp_path / "early.png", budget_ms=500)
        late = screenshot(url, tmp_path / "late.png", budget_ms=3000)
        masks = [drawn_pixels(early), drawn_pixels(late)]
        for mask in masks:
            assert_framed(mask)
        assert np.mean(masks[0][CONTROLS:] != masks[1][CONTROLS:]) > 0.002  # the scene plays
        command.send_signal(signal.SIGINT)
        out, err = command.communicate(timeout=30)
    finally:
        if command.poll() is None:
            command.kill()
            command.wait()
    assert command.returncode == 0
    assert "Traceback" not in err and out.strip().endswith("stopped")
    with pytest.raises(urllib.error.URLError):  # its server is gone with it
        urllib.request.urlopen(url, timeout=5)
