"""Regenerate `urdf/<name>.urdf` of every registered mechanism at its default parameters.

Usage: python tools/generate_urdfs.py [NAME ...]
"""

from __future__ import annotations

import sys
from pathlib import Path

from mechkit.base.atomic import write_text
from mechkit.catalog.registry import get_spec, names

URDF_DIR = Path(__file__).resolve().parent.parent / "urdf"  # the repository's folder, not an installed copy


def main(chosen: list[str]) -> int:
    for name in chosen or names():
        path = write_text(URDF_DIR / f"{name}.urdf", get_spec(name).default_urdf())
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
