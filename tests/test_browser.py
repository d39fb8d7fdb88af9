"""Real-browser checks: each mechanism's page rendered by headless Chromium shows the mechanism.

Skipped only where Chromium is absent. One browser run per mechanism (a few seconds each).
"""

from __future__ import annotations

import pytest

import mechkit
from mechkit import viz
from mechkit.browser import coverage, find_chromium, screenshot
from mechkit.cli import main
from mechkit.exceptions import MethodUnavailable

try:
    find_chromium()
    NO_BROWSER = ""
except MethodUnavailable as err:
    NO_BROWSER = str(err)

pytestmark = pytest.mark.skipif(bool(NO_BROWSER), reason=NO_BROWSER)
BACKGROUND = tuple(round(255 * c) for c in viz.BACKGROUND)
MIN_COVERAGE = 0.02  # fraction of the pixels the mechanism must cover


def assert_shows_a_mechanism(png) -> float:
    background, covered = coverage(png)
    assert max(abs(a - b) for a, b in zip(background, BACKGROUND)) <= 2  # the page drew its scene
    assert covered > MIN_COVERAGE
    return covered


@pytest.mark.parametrize("name", list(mechkit.specs()))
def test_snapshot_png_shows_the_mechanism(name, tmp_path):
    """`mechkit snapshot NAME --png out.png`, offline."""
    png = tmp_path / f"{name}.png"
    assert main(["snapshot", name, "--png", str(png)]) == 0
    assert_shows_a_mechanism(png)
    assert [p.name for p in tmp_path.iterdir()] == [png.name]  # its temporary page is gone


def test_animation_plays(load_cached, tmp_path):
    """The animated page moves: two screenshots at different times differ, each showing the mechanism."""
    page = tmp_path / "sweep.html"
    viz.animation(load_cached("five_bar"), "sweep", page)
    early, late = screenshot(page, tmp_path / "early.png", budget_ms=300), screenshot(page, tmp_path / "late.png",
                                                                                       budget_ms=2500)
    assert_shows_a_mechanism(early)
    assert_shows_a_mechanism(late)
    from PIL import Image, ImageChops

    with Image.open(early) as a, Image.open(late) as b:
        changed = ImageChops.difference(a.convert("RGB"), b.convert("RGB")).convert("L").point(lambda v: v > 12)
        assert sum(changed.getdata()) / (a.width * a.height) > 0.002


@pytest.mark.slow
@pytest.mark.parametrize("name", list(mechkit.specs()))
def test_every_scene_picture_shows_the_mechanism(name, tmp_path):
    m = mechkit.load(name)
    for scene in viz.scenes(m):
        png = tmp_path / f"{scene}.png"
        viz.snapshot_command(m, scene=scene, html=str(tmp_path / f"{scene}.html"), png=str(png))
        assert_shows_a_mechanism(png)
