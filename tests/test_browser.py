"""Real-browser checks: each mechanism's page rendered by headless Chromium shows the mechanism.

Skipped only where Chromium is absent. One browser run per mechanism (a few seconds each).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import mechkit
from mechkit import scenes, viz
from mechkit.base.exceptions import MethodUnavailable
from mechkit.cli import main
from mechkit.viz import gallery, meshcat_page
from mechkit.viz.browser import coverage, find_chromium, screenshot

try:
    find_chromium()
    NO_BROWSER = ""
except MethodUnavailable as err:
    NO_BROWSER = str(err)

pytestmark = pytest.mark.skipif(bool(NO_BROWSER), reason=NO_BROWSER)
BACKGROUND = tuple(round(255 * c) for c in meshcat_page.BACKGROUND)
MIN_COVERAGE = 0.02  # fraction of the pixels the mechanism must cover
GALLERY = Path(__file__).resolve().parent.parent / "docs" / "gallery"


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
        changed = np.asarray(ImageChops.difference(a.convert("RGB"), b.convert("RGB")).convert("L")) > 12
        assert changed.mean() > 0.002


def same_picture(a, b) -> bool:
    """Pixel by pixel, within 12 levels, on all but 0.1 % of the pixels."""
    import numpy as np
    from PIL import Image

    with Image.open(a) as x, Image.open(b) as y:
        if x.size != y.size:
            return False
        diff = np.abs(np.asarray(x.convert("RGB"), dtype=int) - np.asarray(y.convert("RGB"), dtype=int))
    return float(np.mean(diff.max(axis=2) > 12)) < 1e-3


def gallery_is_reproduced(name, tmp_path) -> None:
    png = tmp_path / f"{name}.png"
    gallery.picture(mechkit.load(name), png)
    assert same_picture(png, GALLERY / f"{name}.png"), f"regenerate with: python tools/gallery.py {name}"


def test_gallery_picture_is_reproduced(tmp_path):
    gallery_is_reproduced("four_bar", tmp_path)


@pytest.mark.slow
@pytest.mark.parametrize("name", list(mechkit.specs()))
def test_every_gallery_picture_is_reproduced(name, tmp_path):
    gallery_is_reproduced(name, tmp_path)


@pytest.mark.slow
@pytest.mark.parametrize("name", list(mechkit.specs()))
def test_every_scene_picture_shows_the_mechanism(name, tmp_path):
    m = mechkit.load(name)
    for scene in scenes.scenes(m):
        png = tmp_path / f"{scene}.png"
        viz.snapshot_command(m, scene=scene, html=str(tmp_path / f"{scene}.html"), png=str(png))
        assert_shows_a_mechanism(png)
