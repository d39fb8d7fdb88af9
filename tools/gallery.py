"""Regenerate the README gallery: `docs/gallery/<name>.png` for every registered mechanism, and
`docs/gallery.md` (a table, one picture per mechanism with a one-line caption).

A mechanism whose spec declares scenes is shown by its first scene (last pose solid, three earlier
poses faded); the others at their home assembly. Needs headless Chromium (`apt-get install chromium`).

Usage: python tools/gallery.py [NAME ...]   (default: every registered mechanism; the table always
lists every one, so regenerate all after adding a mechanism)
"""

from __future__ import annotations

import argparse
import math
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import mechkit
from mechkit import viz
from mechkit.base.atomic import write_text
from mechkit.cli.progress import ProgressBars
from mechkit.viz.browser import coverage, screenshot

GALLERY = ROOT / "docs" / "gallery"
TABLE = ROOT / "docs" / "gallery.md"
SIZE = (800, 600)  # pixels
MAX_BYTES = 200_000
MIN_COVERAGE = 0.02  # fraction of pixels the mechanism must cover

# what each mechanism is, in a few words (default: its registry summary)
WHAT = {
    "four_bar": "Planar four-bar crank-rocker (calibration mechanism)",
    "five_bar": "Planar five-bar, two cranks driven (calibration mechanism)",
    "parallel_2t1r": "2T1R parallel mechanism: five-bar limb and two RRR limbs carrying the platform",
    "rocket_gimbal": "Engine gimbal: bracket and engine hinges, two U-P-S servo actuators",
    "spherical_2dof": "2-DOF spherical platform: two RRR limbs and a central Hooke strut",
    "ten_bar": "Radarsat-2 solar-array ten-bar: two motors and a spring-loaded DOF",
    "tetra_3rr3uru": "Tetrahedral 3RR-3URU deployable unit",
    "deployable_9rr12uru": "9RR-12URU deployable mast of tetrahedral units",
}
# what each scene shows (default: its name)
SCENE_WHAT = {
    ("deployable_9rr12uru", "fold"): "the 200 s fold, deployed (faded) to folded (solid)",
    ("tetra_3rr3uru", "fold"): "the 200 s fold, deployed (faded) to folded (solid)",
    ("parallel_2t1r", "motion_law"): "the paper's 5 s motion law, start (faded) to end (solid)",
    ("rocket_gimbal", "swing"): "one period of the engine swing (solid: its start, faded: later phases)",
    ("spherical_2dof", "cone"): "one turn of the platform's cone (solid: its start, faded: later phases)",
    ("ten_bar", "deploy"): "the deployment, stowed (faded) to deployed (solid)",
}
LEGEND = ("Red: actuated joints; dark: passive joints; yellow spheres: loop cuts; dark grey: ground. "
          "Regenerate with `python tools/gallery.py`.")


def picture(mechanism: mechkit.Mechanism, png: Path) -> str:
    """Write the mechanism's picture (checked: under MAX_BYTES, covering MIN_COVERAGE); returns its caption."""
    name = mechanism.spec.name
    own = list(mechanism.spec.scenes)
    with tempfile.TemporaryDirectory(prefix="mechkit-gallery-") as tmp:
        page = Path(tmp) / f"{name}.html"
        if own:
            scene = own[0]
            write_text(page, viz.overlay(mechanism, scene))
            what = SCENE_WHAT.get((name, scene), "last pose solid, earlier ones faded")
            shown = f"{what} (`mechkit snapshot {name} --scene {scene}`)"
        else:
            write_text(page, viz.snapshot(mechanism))
            shown = f"home assembly ({_inputs(mechanism)})"
        screenshot(page, png, size=SIZE)
    size, (_, covered) = png.stat().st_size, coverage(png)
    if size > MAX_BYTES or covered < MIN_COVERAGE:
        raise SystemExit(f"{png}: {size} bytes, mechanism covers {covered:.1%} of the frame")
    return f"{WHAT.get(name, mechanism.spec.summary)}; {shown}."


def _inputs(mechanism: mechkit.Mechanism) -> str:
    """The home input values, in degrees or millimetres (one value when they are all equal)."""
    out = []
    for joint in mechanism.actuated:
        value = float(mechanism.home_q[mechanism.q_index(joint)])
        prismatic = mechanism.model.joints[mechanism.model.getJointId(joint)].shortname().startswith("JointModelP")
        out.append((joint, f"{value * 1000:.0f} mm" if prismatic else f"{math.degrees(value):.1f} deg"))
    if len(out) > 3 and len({value for _, value in out}) == 1:
        return f"its {len(out)} inputs at {out[0][1]}"
    return ", ".join(f"{joint} = {value}" for joint, value in out)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", help="mechanisms to redraw (default: all)")
    names = parser.parse_args(argv).names or list(mechkit.specs())
    GALLERY.mkdir(parents=True, exist_ok=True)
    captions = _read_captions()
    progress = ProgressBars()
    for done, name in enumerate(names, 1):
        png = GALLERY / f"{name}.png"
        captions[name] = picture(mechkit.load(name), png)
        print(f"{png.relative_to(ROOT)}: {png.stat().st_size / 1000:.0f} kB")
        progress("gallery", done, len(names), name)
    rows = [f"| `{name}` | ![{name}](docs/gallery/{name}.png) | {captions.get(name, '(not drawn yet)')} |"
            for name in mechkit.specs()]
    write_text(TABLE, "\n".join(["## Gallery", "", LEGEND, "", "| mechanism | picture | what it shows |",
                                 "|---|---|---|", *rows, ""]))
    print(f"wrote {TABLE.relative_to(ROOT)}")
    return 0


def _read_captions() -> dict[str, str]:
    """Captions already in the table (kept for the mechanisms not redrawn)."""
    if not TABLE.exists():
        return {}
    out = {}
    for line in TABLE.read_text().splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 3 and cells[0].startswith("`"):
            out[cells[0].strip("`")] = cells[2]
    return out


if __name__ == "__main__":
    sys.exit(main())
