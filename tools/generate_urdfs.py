"""Regenerate `urdf/<name>.urdf` of every registered mechanism at its default parameters: its template's text,
then its actuators, home and assembly branch declared (`mechkit.export.urdf`), so that the file alone is the
mechanism (`mechkit.load("urdf/<name>.urdf")` is `mechkit.load(name)`).

Usage: python tools/generate_urdfs.py [NAME ...]
"""

from __future__ import annotations

import sys
from pathlib import Path

from mechkit import load
from mechkit.base.atomic import write_text
from mechkit.catalog.registry import names
from mechkit.export import to_urdf

URDF_DIR = Path(__file__).resolve().parent.parent / "urdf"  # the repository's folder, not an installed copy


def main(chosen: list[str]) -> int:
    for name in chosen or names():
        path = write_text(URDF_DIR / f"{name}.urdf", to_urdf(load(name)))
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
