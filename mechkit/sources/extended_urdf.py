"""Extended URDF (Batto, de Matteis, Mansard; Gepetto's example-parallel-robots): a tree URDF plus a
YAML sidecar beside it (same stem, `.yaml`): `closed_loop: [[frame_a, frame_b], ...]`,
`type: ['3d' | '6d', ...]`, `name_mot: [joint, ...]`.

A 6d pair is a weld cut; a 3d pair is a spherical cut (coincident points). Two 3d pairs joining the
same two bodies at distinct points are one revolute cut about the line through them (the way a
hinge is written with point anchors, and the way `mechkit export` writes one): its frames are the
first pair's, its axis the direction to the second pair, in frame_a's frame.
"""

from __future__ import annotations

import dataclasses
import re
import xml.etree.ElementTree as ET
from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import MalformedDescription
from mechkit.sources.description import Description, read_text
from mechkit.sources.urdf import LOOP_NAMESPACE, build_model, describe_urdf, parse_xml


def sidecar_of(path: Path) -> Path | None:
    """The `.yaml` (or `.yml`) sidecar beside a URDF, if there is one.

    Args:
        path: a URDF file.

    Returns:
        The sidecar, or None.
    """
    for suffix in (".yaml", ".yml"):
        candidate = path.with_suffix(suffix)
        if candidate.is_file():
            return candidate
    return None


def read_extended_urdf(path: Path, sidecar: Path) -> Description:
    """The URDF with the sidecar's pairs as `<mechkit:loop>` elements and its motors as actuators.

    Args:
        path: the tree URDF.
        sidecar: its YAML sidecar (`closed_loop`, `type`, `name_mot`).

    Returns:
        The description.

    Raises:
        MalformedDescription: a sidecar that is not YAML, lacks `closed_loop`, has lists of different
            lengths, an unknown type, or names a frame or a motor the URDF does not have.
    """
    urdf = read_text(path)
    content = _sidecar(sidecar)
    root = parse_xml(urdf, str(path))
    placements = link_placements(root)
    pairs, kinds = content["closed_loop"], [str(k).lower() for k in content["type"]]
    for pair in pairs:
        if not (isinstance(pair, list) and len(pair) == 2 and all(isinstance(f, str) for f in pair)):
            raise MalformedDescription(f"{sidecar}: closed_loop", f"{pair!r} is not a pair of frame names")
        for frame in pair:
            if frame not in placements:
                raise MalformedDescription(f"{sidecar}: closed_loop", f"frame {frame!r} is not a link of {path.name}")
    joints = {j.get("name") for j in root.findall("joint") if j.get("type") != "fixed"}
    motors = tuple(content.get("name_mot") or ())
    for motor in motors:
        if motor not in joints:
            raise MalformedDescription(f"{sidecar}: name_mot", f"{motor!r} is not a moving joint of {path.name}")
    loops = "".join(f"\n  <mechkit:loop {' '.join(f'{k}={quoteattr(v)}' for k, v in attrs.items())}/>"
                    for attrs in _loops(placements, pairs, kinds, sidecar))
    end = urdf.rindex("</robot>")
    text = urdf[:end] + loops + "\n" + urdf[end:]
    if f'xmlns:mechkit="{LOOP_NAMESPACE}"' not in text:
        text = re.sub(r"<robot\b", f'<robot xmlns:mechkit="{LOOP_NAMESPACE}"', text, count=1)
    desc = describe_urdf(text, path, "extended-urdf")  # checks the tree, the inertias and the loops once
    return dataclasses.replace(desc, actuated=motors or desc.actuated)


def link_placements(root: ET.Element) -> dict[str, tuple[str, pin.SE3]]:
    """Where every link is fixed: the body it moves with (the link after its last moving joint) and its
    placement in that body's frame, following fixed joints up the tree.

    Args:
        root: the URDF's <robot> element.

    Returns:
        Link -> (body link, placement (pin.SE3)).
    """
    parent_joint = {j.find("child").get("link"): j for j in root.findall("joint")}
    out: dict[str, tuple[str, pin.SE3]] = {}

    def place(link: str) -> tuple[str, pin.SE3]:
        if link not in out:
            joint = parent_joint.get(link)
            if joint is None or joint.get("type") != "fixed":
                out[link] = (link, pin.SE3.Identity())
            else:
                body, M = place(joint.find("parent").get("link"))
                origin = joint.find("origin")
                xyz = [float(x) for x in (origin.get("xyz", "0 0 0") if origin is not None else "0 0 0").split()]
                rpy = [float(x) for x in (origin.get("rpy", "0 0 0") if origin is not None else "0 0 0").split()]
                out[link] = (body, M * pin.SE3(pin.rpy.rpyToMatrix(*rpy), np.array(xyz)))
        return out[link]

    for link in root.findall("link"):
        place(link.get("name"))
    return out


def _sidecar(sidecar: Path) -> dict:
    import yaml

    try:
        content = yaml.load(read_text(sidecar), Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader))
    except yaml.YAMLError as err:
        raise MalformedDescription(str(sidecar), f"not YAML: {str(err).splitlines()[0]}") from None
    if not isinstance(content, dict) or not isinstance(content.get("closed_loop"), list):
        raise MalformedDescription(str(sidecar), "needs a list 'closed_loop' of frame pairs")
    kinds = content.get("type")
    if not isinstance(kinds, list) or len(kinds) != len(content["closed_loop"]):
        raise MalformedDescription(f"{sidecar}: type", f"needs one type per closed_loop pair, got {kinds!r}")
    for kind in kinds:
        if str(kind).lower() not in ("3d", "6d"):
            raise MalformedDescription(f"{sidecar}: type", f"{kind!r} is not '3d' or '6d'")
    if not isinstance(content.get("name_mot") or [], list):
        raise MalformedDescription(f"{sidecar}: name_mot", "must be a list of joint names")
    return content


def _loops(placements: dict[str, tuple[str, pin.SE3]], pairs: list[list[str]], kinds: list[str],
           sidecar: Path) -> list[dict[str, str]]:
    """Attributes of the `<mechkit:loop>`s of the pairs (3d pairs on the same two bodies merged into hinges)."""
    used = [False] * len(pairs)
    out = []
    for i, ((a, b), kind) in enumerate(zip(pairs, kinds)):
        if used[i]:
            continue
        used[i] = True
        (body_a, Ma), (body_b, _) = placements[a], placements[b]
        if body_a == body_b:
            raise MalformedDescription(f"{sidecar}: closed_loop {[a, b]}", "both frames are on one body")
        attrs = {"name": f"{a}-{b}", "frame_a": a, "frame_b": b, "type": "weld" if kind == "6d" else "spherical"}
        if kind == "3d":
            for k in range(i + 1, len(pairs)):
                (ga_body, Ga), (gb_body, _) = (placements[f] for f in pairs[k])
                if used[k] or kinds[k] != "3d" or (ga_body, gb_body) != (body_a, body_b):
                    continue
                offset = Ma.actInv(Ga.translation)  # second anchor in frame_a (m)
                if np.linalg.norm(offset) > 1e-9:
                    used[k] = True
                    attrs["type"] = "revolute"
                    attrs["axis"] = " ".join(repr(float(x)) for x in offset / np.linalg.norm(offset))
                    break
        out.append(attrs)
    return out


def load_extended_urdf(urdf: str, yaml_text: str) -> tuple[pin.Model, list[pin.RigidConstraintModel], list[str]]:
    """Read an Extended URDF pair the way Gepetto's loader does (model, RigidConstraintModels, motors).

    Every pair is a point (3d) or frame (6d) anchor, as in Gepetto's toolbox; `read_extended_urdf`
    is mechkit's reading (joints, not anchors).

    Args:
        urdf: tree URDF text.
        yaml_text: sidecar text (`closed_loop`, `type`, `name_mot`).

    Returns:
        (the tree model, one RigidConstraintModel per pair (LOCAL frames), the motors' joint names).
    """
    import yaml

    content = yaml.safe_load(yaml_text)
    model = build_model(urdf)
    constraints = []
    for (name_a, name_b), kind in zip(content["closed_loop"], content["type"], strict=True):
        fa, fb = (model.frames[model.getFrameId(n)] for n in (name_a, name_b))
        contact = pin.ContactType.CONTACT_3D if kind.lower() == "3d" else pin.ContactType.CONTACT_6D
        constraints.append(pin.RigidConstraintModel(contact, model, fa.parentJoint, fa.placement, fb.parentJoint,
                                                    fb.placement, pin.ReferenceFrame.LOCAL))
    return model, constraints, list(content["name_mot"])
