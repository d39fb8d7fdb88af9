"""Real-browser checks of the live viewer and of mesh drawings: headless Chromium opens the page that
`mechkit view` serves on 127.0.0.1 and shows a framed, moving mechanism; the command ends cleanly on
Ctrl-C. Skipped only where Chromium is absent."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import urllib.error
import urllib.request
from pathlib import Path

import numpy as np
import pytest

from mechkit import from_urdf
from mechkit.base.exceptions import MethodUnavailable
from mechkit.viz import meshcat_page, snapshot
from mechkit.viz.browser import coverage, find_chromium, screenshot
from mechkit.viz.meshes import MeshSearch

try:
    find_chromium()
    NO_BROWSER = ""
except MethodUnavailable as err:
    NO_BROWSER = str(err)

pytestmark = pytest.mark.skipif(bool(NO_BROWSER), reason=NO_BROWSER)
ROOT = Path(__file__).resolve().parent.parent
BACKGROUND = tuple(round(255 * c) for c in meshcat_page.BACKGROUND)
MIN_COVERAGE = 0.02  # fraction of the pixels the mechanism must cover
CONTROLS = 24  # rows at the top of meshcat's own page taken by its "Open Controls" bar (px)


def drawn_pixels(png) -> np.ndarray:
    """Boolean (rows, columns) mask of the pixels that differ from the page's background."""
    from PIL import Image

    background, covered = coverage(png)
    assert max(abs(a - b) for a, b in zip(background, BACKGROUND)) <= 2  # the page drew its own scene
    assert covered > MIN_COVERAGE
    with Image.open(png) as image:
        rgb = np.asarray(image.convert("RGB"), dtype=int)
    return np.any(np.abs(rgb - np.array(BACKGROUND)) > 12, axis=2)


def assert_framed(mask: np.ndarray) -> None:
    """The drawing is whole: no drawn pixel on the picture's left, right or bottom edge, nor just under the
    controls bar, and it spans a good part of the picture each way."""
    body = mask[CONTROLS:]
    rows, cols = np.nonzero(body)
    assert not body[0].any() and not body[-1].any() and not body[:, 0].any() and not body[:, -1].any()
    assert np.ptp(rows) > 0.3 * body.shape[0] or np.ptp(cols) > 0.3 * body.shape[1]


def test_live_viewer_in_a_real_browser_and_ctrl_c(tmp_path):
    """`mechkit view five_bar --scene sweep`: the served page shows the mechanism framed, two moments of
    the scene differ (it plays), and Ctrl-C ends the command and its server without a traceback."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    command = subprocess.Popen([sys.executable, "-m", "mechkit", "view", "five_bar", "--scene", "sweep"],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
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


def test_mesh_drawing_in_a_real_browser(tmp_path):
    """A URDF drawn only by mesh visuals (STL and OBJ fixtures) shows them, framed."""
    from test_viewer_meshes import MESHES, arm

    page = tmp_path / "arm.html"
    snapshot(from_urdf(arm("box.stl", "box.obj"), name="arm"), np.array([0.7, -0.5]), page,
             meshes=MeshSearch.of(MESHES))
    mask = drawn_pixels(screenshot(page, tmp_path / "arm.png"))
    assert_framed(mask)
