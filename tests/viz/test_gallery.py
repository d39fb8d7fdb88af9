"""`mechkit.viz.gallery`: the committed gallery agrees with the registry, and its pictures are reproduced
(in a real browser, where Chromium is present)."""

from __future__ import annotations

import pytest
from tests_support import ROOT

import mechkit
from mechkit.viz import gallery

from .in_browser import needs_browser

GALLERY = ROOT / "docs" / "gallery"


@pytest.mark.parametrize("name", list(mechkit.specs()))
def test_gallery_has_the_mechanism(name):
    """The committed gallery agrees with the registry (regenerate with tools/gallery.py)."""
    png = ROOT / "docs" / "gallery" / f"{name}.png"
    assert png.is_file() and png.stat().st_size < 200_000
    rows = [
        line for line in (ROOT / "docs" / "gallery.md").read_text().splitlines() if line.startswith(f"| `{name}` |")
    ]
    assert len(rows) == 1 and f"(docs/gallery/{name}.png)" in rows[0] and "not drawn yet" not in rows[0]


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


@needs_browser
def test_gallery_picture_is_reproduced(tmp_path):
    gallery_is_reproduced("four_bar", tmp_path)


@needs_browser
@pytest.mark.slow
@pytest.mark.parametrize("name", list(mechkit.specs()))
def test_every_gallery_picture_is_reproduced(name, tmp_path):
    gallery_is_reproduced(name, tmp_path)
