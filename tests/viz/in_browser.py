"""Real-browser checks: the marker that skips them where Chromium is absent, and what a screenshot of
a mechanism must show (the page's background, a mechanism covering part of it, framed)."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import MethodUnavailable
from mechkit.viz import meshcat_page
from mechkit.viz.browser import coverage, find_chromium

try:
    find_chromium()
    NO_BROWSER = ""
except MethodUnavailable as err:
    NO_BROWSER = str(err)

#: Mark of the tests that run headless Chromium: skipped, saying why, where it is absent.
needs_browser = pytest.mark.skipif(bool(NO_BROWSER), reason=NO_BROWSER)
BACKGROUND = tuple(round(255 * c) for c in meshcat_page.BACKGROUND)
MIN_COVERAGE = 0.02  # fraction of the pixels the mechanism must cover
CONTROLS = 24  # rows at the top of meshcat's own page taken by its "Open Controls" bar (px)


def assert_shows_a_mechanism(png) -> float:
    """The page drew its own scene and a mechanism covers more than `MIN_COVERAGE` of it; that fraction."""
    background, covered = coverage(png)
    assert max(abs(a - b) for a, b in zip(background, BACKGROUND)) <= 2  # the page drew its scene
    assert covered > MIN_COVERAGE
    return covered


def drawn_pixels(png) -> np.ndarray:
    """Boolean (rows, columns) mask of the pixels that differ from the page's background (which must show
    a mechanism)."""
    from PIL import Image

    assert_shows_a_mechanism(png)
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
