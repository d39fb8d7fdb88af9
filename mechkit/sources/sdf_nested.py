"""Nested `<model>`s of an SDFormat model, flattened into it with their names scoped by `::`, as libsdformat
reads them (SDFormat 1.8 and later: sdformat.org/spec?ver=1.9&elem=model, "model" within "model"; the name
scoping and frame rules of sdformat.org/tutorials?tut=composition_proposal and
sdformat.org/tutorials?tut=pose_frame_semantics_proposal):

- a link, joint or `<frame>` named `x` in nested model `arm` is `arm::x` in the enclosing model (deeper
  nestings `arm::hand::x`); the names an element of `arm` refers to (`<parent>`, `<child>`,
  `<gearbox_reference_body>`, `relative_to`, `attached_to`, `expressed_in`) are in `arm`'s scope, so they get
  the same prefix; `__model__` there is `arm`'s model frame, and `world` stays the world.
- the nested model's own frame is the `<frame>` `arm` (also `arm::__model__`): its `<pose>` is relative to
  the enclosing model's frame unless `relative_to` names a frame of the enclosing scope; it is attached to
  the nested model's canonical link (`canonical_link`, else its first link, else its first nested model's).
  A nested model's link without a `relative_to` is placed in `arm`'s frame, a `<frame>` without
  `attached_to` is attached to it.

Refused by name: nested models before SDFormat 1.8, `<include>`, `placement_frame`, a `<static>` nested
model, a nested model without a link.
"""

from __future__ import annotations

import copy
import xml.etree.ElementTree as ET

from mechkit.base.exceptions import MalformedDescription
from mechkit.sources.sdf_frames import MODEL, boolean

#: Attributes (on any element) and joint children whose values name frames or links.
ATTRIBUTES = ("relative_to", "attached_to", "expressed_in")
TEXTS = ("parent", "child", "gearbox_reference_body")


def flattened(model: ET.Element, version: tuple[int, int]) -> ET.Element:
    """`model` with its nested models (at any depth) flattened into it (see the module docstring).

    Args:
        model: the top `<model>` element.
        version: the file's SDFormat version (major, minor).

    Returns:
        `model` itself when it nests nothing, else a flattened copy: links, joints and `<frame>`s only
        in its scope, with scoped names.

    Raises:
        MalformedDescription: what the module docstring refuses, by name.
    """
    where = f"SDF model {model.get('name') or 'model'!r}"
    if model.find("include") is not None:
        raise MalformedDescription(where, "<include> is not read: paste the included model in as a nested <model>")
    if model.find("model") is None:
        return model
    if version < (1, 8):
        raise MalformedDescription(where, "nested <model>s are read from SDFormat 1.8 (names scoped by ::)")
    out = ET.Element("model", dict(model.attrib))
    for child in model:  # in file order (a link's first parent joint in it is its tree joint)
        if child.tag == "model":
            _inline(out, child, "")
        else:
            out.append(_rewritten(copy.deepcopy(child), ""))
    return out


def _scoped(name: str, scope: str) -> str:
    """A name of scope `scope` (a model's name, '' at the top) in the top model's scope."""
    name = name.strip()
    if name == "world":
        return name
    full = f"{scope}::{name}" if scope else name
    return full.removesuffix(f"::{MODEL}") if full != MODEL else full


def _rewritten(element: ET.Element, scope: str) -> ET.Element:
    """`element` (a copy) with every name it refers to put in the top model's scope."""
    for node in element.iter():
        for key in ATTRIBUTES:
            if node.get(key):
                node.set(key, _scoped(node.get(key), scope))
        if node is not element and node.tag in TEXTS and node.text:
            node.text = _scoped(node.text, scope)
    return element


def _inline(out: ET.Element, nested: ET.Element, scope: str) -> None:
    """Append nested model `nested` of scope `scope` (and its own nested models) to `out`, flattened."""
    name = _scoped(nested.get("name") or "", scope)
    where = f"SDF model {name!r}"
    if not nested.get("name") or "::" in nested.get("name"):
        raise MalformedDescription(where, "a nested <model> needs a name without '::'")
    if nested.find("include") is not None:
        raise MalformedDescription(where, "<include> is not read: paste the included model in as a nested <model>")
    if nested.get("placement_frame"):
        raise MalformedDescription(where, "placement_frame is not read: give the nested model's <pose> instead")
    if boolean(nested.findtext("static"), where, "<static>"):
        raise MalformedDescription(where, "a <static> nested model (fixed to the world) is not read")
    frame = ET.SubElement(out, "frame", {"name": name, "attached_to": _canonical(nested, name)})
    pose = copy.deepcopy(nested.find("pose")) if nested.find("pose") is not None else ET.Element("pose")
    pose.set("relative_to", _scoped(pose.get("relative_to") or MODEL, scope))
    frame.append(pose)
    for child in nested:
        if child.tag in ("link", "joint", "frame"):
            element = _rewritten(copy.deepcopy(child), name)
            element.set("name", _scoped(child.get("name") or "", name))
            if child.tag == "frame" and not child.get("attached_to"):
                element.set("attached_to", name)
            if child.tag == "link" and (child.find("pose") is None or not child.find("pose").get("relative_to")):
                placed = element.find("pose")
                if placed is None:
                    placed = ET.SubElement(element, "pose")
                placed.set("relative_to", name)
            out.append(element)
        elif child.tag == "model":
            _inline(out, child, name)


def _canonical(model: ET.Element, name: str) -> str:
    """The scoped name of a nested model's canonical link (`canonical_link`, else its first link, else its
    first nested model's)."""
    if model.get("canonical_link"):
        return _scoped(model.get("canonical_link"), name)
    if model.find("link") is not None:
        return _scoped(model.find("link").get("name") or "", name)
    if model.find("model") is not None:
        first = model.find("model")
        return _canonical(first, _scoped(first.get("name") or "", name))
    raise MalformedDescription(f"SDF model {name!r}", "a nested model without a link (no canonical link)")
