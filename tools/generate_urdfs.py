"""Regenerate `urdf/<name>.urdf` of every registered mechanism at its default parameters.

Usage: python tools/generate_urdfs.py [NAME ...]
"""

from __future__ import annotations

import sys

from mechkit.atomic import write_text
from mechkit.registry import URDF_DIR, specs


def main(names: list[str]) -> int:
    for name in names or list(specs()):
        path = write_text(URDF_DIR / f"{name}.urdf", specs()[name].default_urdf())
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
