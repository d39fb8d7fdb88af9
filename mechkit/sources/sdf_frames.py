"""The frames of an SDFormat model: its links, joints and `<frame>`s by name, each one's pose in the
model frame (SDFormat before 1.7: links in the model frame, joints in their child link's; from 1.7,
`relative_to` any frame, frames `attached_to` one), the link a frame stands for, a joint's axis in
its own frame (`use_parent_model_frame` before 1.7, `expressed_in` from 1.7), and the numbers of
`<pose>` elements (`degrees`, `rotation_format`)."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import MalformedDescription

#: The name of the model frame.
MODEL = "__model__"


def sdf_version(root: ET.Element, where: str) -> tuple[int, int]:
    """The `<sdf version>` of a file.

    Args:
        root: the `<sdf>` element.
        where: the file, for messages.

    Returns:
        (major, minor).

    Raises:
        MalformedDescription: a version that is not two integers.
    """
    text = root.get("version", "")
    try:
        major, minor = (int(x) for x in text.split("."))
    except ValueError:
        raise MalformedDescription(where, f"<sdf version={text!r}>: expected a version such as 1.6") from None
    return major, minor


def boolean(text: str | None, where: str, what: str, default: bool = False) -> bool:
    """An SDFormat boolean as libsdformat reads it: "true" or "1", "false" or "0" (any case, spaces around).

    Args:
        text: the attribute's or element's text (None: absent).
        where: what is read, for messages.
        what: the attribute or element, for messages.
        default: the value of an absent one.

    Returns:
        The value.

    Raises:
        MalformedDescription: any other text.
    """
    if text is None:
        return default
    word = text.strip().lower()
    if word not in ("true", "1", "false", "0"):
        raise MalformedDescription(where, f"{what}={text!r} is not a boolean (true, false, 1 or 0)")
    return word in ("true", "1")


def numbers(element: ET.Element | None, where: str, count: int, default: tuple[float, ...]) -> np.ndarray:
    """The whitespace-separated numbers of an element's text.

    Args:
        element: the element, or None.
        where: what is read, for messages.
        count: how many numbers it must hold.
        default: the numbers of an absent or empty element.

    Returns:
        The numbers (count,).

    Raises:
        MalformedDescription: not `count` finite numbers.
    """
    if element is None or not (element.text or "").strip():
        return np.array(default, dtype=float)
    try:
        values = np.array([float(x) for x in element.text.split()])
    except ValueError:
        raise MalformedDescription(where, f"<{element.tag}> {element.text.strip()!r} is not {count} numbers") from None
    if values.shape != (count,) or not np.all(np.isfinite(values)):
        raise MalformedDescription(where, f"<{element.tag}> {element.text.strip()!r} is not {count} finite numbers")
    return values


def number(element: ET.Element, tag: str, where: str, default: float | None) -> float:
    """The number a child element holds.

    Args:
        element: the parent element.
        tag: the child's tag.
        where: what is read, for messages.
        default: the value when the child is absent; None: the child is required.

    Returns:
        The number.

    Raises:
        MalformedDescription: a required child missing, or not one finite number.
    """
    child = element.find(tag)
    if child is None and default is None:
        raise MalformedDescription(where, f"missing <{tag}>")
    return float(default if child is None else numbers(child, where, 1, (default or 0.0,))[0])


class SdfFrames:
    """The named frames of one SDFormat model (links, joints, `<frame>`s) and their poses.

    Args:
        model: the `<model>` element, its nested models flattened (`mechkit.sources.sdf_nested.flattened`).
        version: the file's SDFormat version (major, minor).
        guidance: the joints preferred as tree joints (kept for the reader).

    Raises:
        MalformedDescription: a missing or repeated name, no link.
    """

    def __init__(self, model: ET.Element, version: tuple[int, int], guidance: tuple[str, ...]):
        self.element, self.version, self.guidance = model, version, guidance
        self.name = model.get("name") or "model"
        self.items: dict[str, dict[str, ET.Element]] = {"link": {}, "joint": {}, "frame": {}}
        for kind, table in self.items.items():
            for element in model.findall(kind):
                name = element.get("name")
                if not name or name in table or (version >= (1, 7) and any(name in t for t in self.items.values())):
                    raise MalformedDescription(f"SDF {kind} {name!r}", "missing or repeated name")
                table[name] = element
        if not self.items["link"]:
            raise MalformedDescription(f"SDF model {self.name!r}", "has no link")
        self.poses: dict[str, pin.SE3] = {}
        self.world = self._pose(model.find("pose"), f"SDF model {self.name!r}")[0]  # model frame in the world

    def _pose(self, element: ET.Element | None, where: str) -> tuple[pin.SE3, str | None]:
        """(placement, the frame it is relative to, None for the default) of a `<pose>`."""
        if element is None:
            return pin.SE3.Identity(), None
        if element.get("frame"):
            raise MalformedDescription(
                where, "the <pose frame> attribute (SDFormat 1.5/1.6) is not read: write SDFormat 1.7 relative_to"
            )
        quat = element.get("rotation_format", "euler_rpy") == "quat_xyzw"
        if element.get("rotation_format", "euler_rpy") not in ("euler_rpy", "quat_xyzw"):
            raise MalformedDescription(where, f"rotation_format {element.get('rotation_format')!r} is not read")
        v = numbers(element, where, 7 if quat else 6, (0.0,) * (7 if quat else 6))
        if quat:
            rotation = pin.Quaternion(v[6], v[3], v[4], v[5]).normalized().matrix()
        else:
            degrees = boolean(element.get("degrees"), where, "<pose degrees>")
            rotation = pin.rpy.rpyToMatrix(*(np.radians(v[3:]) if degrees else v[3:]))
        return pin.SE3(rotation, v[:3]), element.get("relative_to") or None

    def frame(self, name: str, stack: tuple[str, ...] = ()) -> pin.SE3:
        """A frame's pose in the model frame, in the file's configuration.

        Args:
            name: a link, joint or `<frame>` name, `__model__` or `world`.
            stack: the frames whose poses wait on this one (to name a cycle).

        Returns:
            Its placement in the model frame.

        Raises:
            MalformedDescription: no such frame, a pose cycle, relative_to before SDFormat 1.7.
        """
        if name == MODEL:
            return pin.SE3.Identity()
        if name == "world":
            return self.world.inverse()
        if name in self.poses:
            return self.poses[name]
        kind = next((k for k, table in self.items.items() if name in table), None)
        where = f"SDF {stack[-1] if stack else 'frame'}" if kind is None else f"SDF {kind} {name!r}"
        if kind is None:
            raise MalformedDescription(where, f"relative_to / attached_to / expressed_in {name!r}: no such frame")
        if name in stack:
            raise MalformedDescription(where, "pose cycle: " + " -> ".join((*stack[stack.index(name) :], name)))
        element = self.items[kind][name]
        placement, relative = self._pose(element.find("pose"), where)
        if relative is not None and self.version < (1, 7):
            raise MalformedDescription(where, "relative_to needs SDFormat 1.7 or later")
        default = (
            self._end(element, "child", where)
            if kind == "joint"
            else element.get("attached_to") or MODEL
            if kind == "frame"
            else MODEL
        )
        self.poses[name] = self.frame(relative or default, (*stack, name)) * placement
        return self.poses[name]

    def _end(self, joint: ET.Element, tag: str, where: str) -> str:
        """A joint's parent or child link (`world` allowed as a parent)."""
        return self.link_of((joint.findtext(tag) or "").strip(), f"<{tag}>", where, tag == "parent")

    def link_of(self, name: str, what: str, where: str, world: bool = False) -> str:
        """The link a frame name stands for: a link, or what a `<frame>` is attached to, or a joint's child.

        Args:
            name: a link, joint or frame name.
            what: what names it, for messages (e.g. "<parent>").
            where: the element read, for messages.
            world: whether `world` is allowed (a joint's parent).

        Returns:
            The link's name (or "world").

        Raises:
            MalformedDescription: an attached_to cycle, or a name that leads to no link of the model.
        """
        seen: list[str] = []
        while name in self.items["frame"] or name in self.items["joint"]:
            if name in seen:
                raise MalformedDescription(where, f"{what} {name!r}: attached_to cycle")
            seen.append(name)
            frame = self.items["frame"].get(name)
            name = (
                (frame.get("attached_to") or MODEL)
                if frame is not None
                else (self.items["joint"][name].findtext("child") or "").strip()
            )
        if name not in self.items["link"] and not (world and name == "world"):
            raise MalformedDescription(where, f"{what} {name!r} is not a link of the model")
        return name

    def axis(self, joint: ET.Element, tag: str, where: str) -> np.ndarray:
        """A joint's `axis` / `axis2` as a unit vector in the joint frame.

        Args:
            joint: the `<joint>` element.
            tag: "axis" or "axis2".
            where: the joint, for messages.

        Returns:
            The unit axis (3,) in the joint's frame.

        Raises:
            MalformedDescription: the axis missing or zero.
        """
        element = joint.find(tag)
        if element is None:
            raise MalformedDescription(where, f"missing <{tag}>")
        xyz = element.find("xyz")
        vector = numbers(xyz, where, 3, (0.0, 0.0, 1.0))
        if not np.any(vector):
            raise MalformedDescription(where, f"<{tag}><xyz> is zero")
        vector = vector / np.max(np.abs(vector))  # scaled first: the norm of 1e300 components would overflow
        if self.version < (1, 7):
            model_frame = boolean(element.findtext("use_parent_model_frame"), where, "<use_parent_model_frame>")
            frame = MODEL if model_frame else None
        else:
            frame = xyz.get("expressed_in") if xyz is not None else None
        R = self.frame(joint.get("name")).rotation
        if frame is not None:
            vector = R.T @ self.frame(frame, (joint.get("name"),)).rotation @ vector
        return vector / np.linalg.norm(vector)
