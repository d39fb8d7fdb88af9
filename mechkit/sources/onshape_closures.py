"""onshape-to-robot's loop-closing frames in a URDF, read as loop closures.

onshape-to-robot (https://onshape-to-robot.readthedocs.io, "Handling kinematic loops") turns an Onshape mate
named `closing_<name>` into two frames, `closing_<name>_1` and `closing_<name>_2`, at the mate connector on
each of the two parts; for a revolute mate, two more, `closing_<name>_1_z` and `closing_<name>_2_z`, 0.1 m
further along the connector's z axis (the hinge). In a URDF each frame is a dummy link on a fixed joint
from its part (source: Rhoban/onshape-to-robot, `assembly.py` "Processing loop closing frames" and
`exporter_urdf.py` `add_frame`; its MJCF exporter joins the same frames by `connect` equalities by site,
which `mechkit.sources.mjcf` reads).

Read here: each `closing_<name>_1` / `closing_<name>_2` pair of links is a cut `closing_<name>` between
them, revolute about their common z axis when the `_z` pair is there (each `_z` link where the other's
is, relative to its frame, on the connector's z axis), else spherical (the coincident points the frames
say; a fastened or slider mate writes the same pair, which the URDF cannot tell from a ball: declare it
as `<mechkit:loop type="weld">` on the two frames, which then replaces this reading). A pair a
`<mechkit:loop>` already joins is left to it.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from collections.abc import Sequence

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import MalformedDescription
from mechkit.core import LoopClosure

#: A closing frame's link name: closing_<name>_<1 or 2>, optionally _z.
CLOSING = re.compile(r"^(closing_.+)_([12])(_z)?$")


def closing_frames(root: ET.Element, declared: Sequence[LoopClosure] = ()) -> tuple[LoopClosure, ...]:
    """The cuts onshape-to-robot's closing frames declare (see the module docstring).

    Args:
        root: the URDF's `<robot>` element.
        declared: the loops the file declares otherwise (`<mechkit:loop>`); a pair one of them joins is
            not read again.

    Returns:
        One cut per `closing_<name>` pair, in the order of the `_1` links.

    Raises:
        MalformedDescription: a closing frame without its other half, `_z` frames on another part than
            their frame or that do not mark one axis, each named.
    """
    links = [link.get("name") or "" for link in root.findall("link")]
    found: dict[str, dict[str, str]] = {}
    for name in links:
        match = CLOSING.match(name)
        if match:
            found.setdefault(match[1], {})[match[2] + (match[3] or "")] = name
    taken = {frozenset((c.frame_a, c.frame_b)) for c in declared}
    out = []
    for base, frames in found.items():
        for side in ("1", "2", "1_z", "2_z"):
            other = {"1": "2", "2": "1", "1_z": "2_z", "2_z": "1_z"}[side]
            if side in frames and other not in frames:
                raise MalformedDescription(
                    f"URDF link {frames[side]!r}",
                    f"an onshape-to-robot closing frame without its other half {base}_{other}",
                )
        if "1" not in frames:
            raise MalformedDescription(f"URDF link {frames['1_z']!r}", f"no {base}_1 and {base}_2 beside it")
        if frozenset((frames["1"], frames["2"])) in taken:
            continue
        axis = _axis(root, frames) if "1_z" in frames else None
        out.append(
            LoopClosure(
                base,
                "spherical" if axis is None else "revolute",
                frames["1"],
                frames["2"],
                axis,
                explicit_rows=False,
            )
        )
    return tuple(out)


def _axis(root: ET.Element, frames: dict[str, str]) -> np.ndarray:
    """The hinge axis in frame `_1`'s frame: the way to `_1_z` from `_1` (on one part: Pinocchio's frames
    of the URDF on one joint), which must be the way to `_2_z` from `_2` in `_2`'s frame (onshape-to-robot
    puts both 0.1 m along the connector's z)."""
    model = pin.buildModelFromXML(ET.tostring(root, encoding="unicode"))
    ways = []
    for side in ("1", "2"):
        at, at_z = (model.frames[model.getFrameId(frames[s], pin.FrameType.BODY)] for s in (side, f"{side}_z"))
        if at.parentJoint != at_z.parentJoint:
            raise MalformedDescription(
                f"URDF link {frames[side + '_z']!r}", f"does not move with {frames[side]!r} (another part)"
            )
        ways.append(at.placement.actInv(at_z.placement).translation)
    length = np.linalg.norm(ways[0])
    if length < 1e-9 or np.linalg.norm(ways[1] - ways[0]) > 1e-9 * max(1.0, length):
        raise MalformedDescription(
            f"URDF links {frames['1_z']!r}, {frames['2_z']!r}",
            f"do not mark one hinge axis: {np.round(ways[0], 12)} from {frames['1']!r}, "
            f"{np.round(ways[1], 12)} from {frames['2']!r}, each in its own frame",
        )
    return ways[0] / length
