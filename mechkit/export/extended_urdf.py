"""Extended URDF export (Batto, de Matteis, Mansard; Gepetto's example-parallel-robots): the tree URDF plus a
YAML sidecar `closed_loop: [[frame_a, frame_b], ...]`, `type: ['3d' | '6d', ...]`, `name_mot`,
`joint_name`, `joint_type`. A 3d pair is a point anchor, 6d a weld. A revolute cut with spatial
rows becomes two 3d pairs; the second pair's frames (`<frame>_axis`) are added to the URDF on
fixed joints, `AXIS_ANCHOR_OFFSET` along the axis.

The URDF keeps mechkit's other elements (e.g. the ten-bar's `<mechkit:spring>`, which other
readers ignore) and gains a `<mechkit:home joint value>` per actuated joint: the home inputs, so
that `mechkit.load` of the pair assembles the same default configuration (on the branch nearest its
guess: the format has no place for one).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from typing import TYPE_CHECKING

import numpy as np
import pinocchio as pin
import yaml

from mechkit.base.exceptions import MethodUnavailable
from mechkit.core import AXIS_ANCHOR_OFFSET
from mechkit.export.urdf import add_mimics, source_text
from mechkit.export.xmltext import numbers as _fmt
from mechkit.sources.urdf import LOOP_NAMESPACE

if TYPE_CHECKING:
    from mechkit.core import CutRows
    from mechkit.mechanism import Mechanism


def to_extended_urdf(mech: Mechanism) -> tuple[str, str]:
    """The mechanism in the Extended URDF convention: a tree URDF and its YAML sidecar.

    Args:
        mech: the mechanism.

    Returns:
        (URDF text, YAML sidecar text).

    Raises:
        MethodUnavailable: a hooke or prismatic cut (no 3d/6d equivalent).
    """
    robot = ET.fromstring(source_text(mech, "extended-urdf export"))
    pairs: list[tuple[str, str]] = []
    kinds: list[str] = []
    frame_parent = {j.find("child").get("link"): j for j in robot.findall("joint")}
    for cut in mech.cuts:
        c = cut.closure
        if c.kind in ("hooke", "prismatic"):
            raise MethodUnavailable(
                "extended-urdf export", f"cut {c.name!r} is {c.kind}: the sidecar has only 3d and 6d pairs"
            )
        pairs.append((c.frame_a, c.frame_b))
        kinds.append("6d" if c.kind == "weld" else "3d")
        if c.kind == "revolute" and c.rows != "planar":
            extra = []
            for frame in (c.frame_a, c.frame_b):
                if frame not in frame_parent:
                    raise MethodUnavailable("extended-urdf export", f"frame {frame!r} is not a URDF link on a joint")
                # the closure axis is given in frame_a's frame, and both frames share orientation when closed
                name = f"{frame}_axis"
                ET.SubElement(robot, "link", name=name)
                j = ET.SubElement(robot, "joint", name=f"{name}_fixed", type="fixed")
                ET.SubElement(j, "parent", link=frame)
                ET.SubElement(j, "child", link=name)
                axis_in_frame = c.axis if frame == c.frame_a else frame_b_vector(mech, cut, c.axis)
                ET.SubElement(j, "origin", xyz=_fmt(AXIS_ANCHOR_OFFSET * axis_in_frame), rpy="0 0 0")
                extra.append(name)
            pairs.append((extra[0], extra[1]))
            kinds.append("3d")
    add_mimics(mech, robot, "extended-urdf export")  # couplings the text does not hold (an SDFormat gearbox)
    for loop in [el for el in robot if el.tag.endswith("}loop") or el.tag.endswith("}home") or el.tag == "loop"]:
        robot.remove(loop)
    for joint in mech.actuated:
        ET.SubElement(
            robot, f"{{{LOOP_NAMESPACE}}}home", joint=joint, value=repr(float(mech.home_q[mech.q_index(joint)]))
        )
    ET.register_namespace("mechkit", LOOP_NAMESPACE)
    ET.indent(robot)
    urdf = '<?xml version="1.0" ?>\n' + ET.tostring(robot, encoding="unicode") + "\n"
    sidecar = {
        "closed_loop": [list(p) for p in pairs],
        "type": kinds,
        "name_mot": list(mech.actuated),
        "joint_name": [],
        "joint_type": [],
    }
    return urdf, yaml.safe_dump(sidecar, sort_keys=False, default_flow_style=None)


def frame_b_vector(mech: Mechanism, cut: CutRows, vector: np.ndarray) -> np.ndarray:
    """A vector given in a cut's frame_a, expressed in its frame_b at the home assembly (loop closed).

    Args:
        mech: the mechanism.
        cut: one of its cuts.
        vector: a 3-vector in the cut's frame_a.

    Returns:
        The same vector in frame_b, shape (3,).
    """
    pin.framesForwardKinematics(mech.model, mech.data, mech.home_q)
    Ra = mech.data.oMf[cut.frame_a].rotation
    Rb = mech.data.oMf[cut.frame_b].rotation
    return Rb.T @ Ra @ np.asarray(vector, dtype=float)
