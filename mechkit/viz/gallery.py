"""The README gallery: one picture per registered mechanism, and the table of them with captions.

A mechanism whose spec declares scenes is shown by its first scene (last pose solid, three earlier
poses faded); the others at their home assembly. Captions are read from the spec (`caption`, else
the summary; `scene_captions`). Pictures need headless Chromium (`mechkit.viz.browser`).
`tools/gallery.py` regenerates `docs/gallery/<name>.png` and `docs/gallery.md` with them.
"""

from __future__ import annotations

import math
import tempfile
from collections.abc import Iterable, Mapping
from pathlib import Path

from mechkit.base.atomic import write_text
from mechkit.base.exceptions import OutputError
from mechkit.mechanism import Mechanism
from mechkit.viz.browser import coverage, screenshot
from mechkit.viz.pages import overlay, snapshot

SIZE = (800, 600)  # pixels
MAX_BYTES = 200_000
MIN_COVERAGE = 0.02  # fraction of pixels the mechanism must cover
LEGEND = (
    "Red: actuated joints; dark: passive joints; yellow spheres: loop cuts; dark grey: ground. "
    "Regenerate with `python tools/gallery.py`."
)


def picture(mechanism: Mechanism, png: Path) -> str:
    """Write the mechanism's picture and return its caption.

    Args:
        mechanism: the mechanism to draw.
        png: the PNG file to write.

    Returns:
        The caption: what the mechanism is, and what the picture shows.

    Raises:
        OutputError: the picture is over `MAX_BYTES`, or the mechanism covers less than `MIN_COVERAGE`.
        MethodUnavailable: no Chromium to take the screenshot.
    """
    spec = mechanism.spec
    own = list(spec.scenes)
    with tempfile.TemporaryDirectory(prefix="mechkit-gallery-") as tmp:
        page = Path(tmp) / f"{spec.name}.html"
        if own:
            scene = own[0]
            write_text(page, overlay(mechanism, scene))
            what = spec.scene_captions.get(scene, "last pose solid, earlier ones faded")
            shown = f"{what} (`mechkit snapshot {spec.name} --scene {scene}`)"
        else:
            write_text(page, snapshot(mechanism))
            shown = f"home assembly ({home_inputs(mechanism)})"
        screenshot(page, png, size=SIZE)
    size, (_, covered) = Path(png).stat().st_size, coverage(png)
    if size > MAX_BYTES or covered < MIN_COVERAGE:
        raise OutputError(png, f"{size} bytes, the mechanism covers {covered:.1%} of the frame")
    return f"{spec.caption or spec.summary}; {shown}."


def home_inputs(mechanism: Mechanism) -> str:
    """The home input values, in degrees or millimetres (one value when they are all equal).

    Args:
        mechanism: the mechanism.

    Returns:
        The text, e.g. "crank = 34.4 deg", or "its 7 inputs at 40.0 deg".
    """
    out = []
    for joint in mechanism.actuated:
        value = float(mechanism.home_q[mechanism.q_index(joint)])
        prismatic = mechanism.model.joints[mechanism.model.getJointId(joint)].shortname().startswith("JointModelP")
        out.append((joint, f"{value * 1000:.0f} mm" if prismatic else f"{math.degrees(value):.1f} deg"))
    if len(out) > 3 and len({value for _, value in out}) == 1:
        return f"its {len(out)} inputs at {out[0][1]}"
    return ", ".join(f"{joint} = {value}" for joint, value in out)


def table(names: Iterable[str], captions: Mapping[str, str]) -> str:
    """The gallery page (markdown): the legend and one row per mechanism, its picture and caption.

    Args:
        names: the mechanisms, in order.
        captions: mechanism -> caption.

    Returns:
        The markdown text.
    """
    rows = [
        f"| `{name}` | ![{name}](docs/gallery/{name}.png) | {captions.get(name, '(not drawn yet)')} |" for name in names
    ]
    return "\n".join(
        ["## Gallery", "", LEGEND, "", "| mechanism | picture | what it shows |", "|---|---|---|", *rows, ""]
    )


def read_captions(text: str) -> dict[str, str]:
    """The captions of a gallery page (kept for the mechanisms not redrawn), by mechanism.

    Args:
        text: the gallery page's markdown.

    Returns:
        Mechanism -> caption.
    """
    out = {}
    for line in text.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 3 and cells[0].startswith("`"):
            out[cells[0].strip("`")] = cells[2]
    return out
