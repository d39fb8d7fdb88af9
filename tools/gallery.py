"""Regenerate the README gallery: `docs/gallery/<name>.png` for every registered mechanism, and
`docs/gallery.md` (a table, one picture per mechanism with a one-line caption), by
`mechkit.viz.gallery`. Needs headless Chromium (`apt-get install chromium`).

Usage: python tools/gallery.py [NAME ...]   (default: every registered mechanism; the table always
lists every one, so regenerate all after adding a mechanism)
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import mechkit
from mechkit.base.atomic import write_text
from mechkit.base.exceptions import MechkitError
from mechkit.cli.progress import ProgressBars
from mechkit.viz.gallery import picture, read_captions, table

ROOT = Path(__file__).resolve().parent.parent
GALLERY = ROOT / "docs" / "gallery"
TABLE = ROOT / "docs" / "gallery.md"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", help="mechanisms to redraw (default: all)")
    names = parser.parse_args(argv).names or list(mechkit.specs())
    GALLERY.mkdir(parents=True, exist_ok=True)
    captions = read_captions(TABLE.read_text()) if TABLE.exists() else {}
    progress = ProgressBars()
    try:
        for done, name in enumerate(names, 1):
            png = GALLERY / f"{name}.png"
            captions[name] = picture(mechkit.load(name), png)
            print(f"{png.relative_to(ROOT)}: {png.stat().st_size / 1000:.0f} kB")
            progress("gallery", done, len(names), name)
    except MechkitError as err:
        print(f"error: {err}", file=sys.stderr)
        return 1
    write_text(TABLE, table(mechkit.specs(), captions))
    print(f"wrote {TABLE.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
