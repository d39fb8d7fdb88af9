"""The URDF element `<mechkit:strut>`: a point-to-point spring, damper and force between two links
(`mechkit.forces.PointToPoint`; a vibration isolator's strut, a gas spring, an actuator modelled as a
force).

    <mechkit:strut name="isolator" frame_a="ground" point_a="0.1 0 0.15" frame_b="rocker_link"
                   point_b="0.11 0 0" stiffness="200" length="0.1" damping="3" force="0"/>

`frame_a`, `frame_b`: the links the points are fixed in; `point_a`, `point_b`: the points in
them (m, default the frames' origins); `stiffness` (N/m), `length` the spring's free length (m, needed
with a stiffness), `damping` (N s/m), `force` a constant force along the line (N, positive pushes the
points apart). Every number but the names defaults to 0.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

from mechkit.base.exceptions import InvalidParameters, MalformedDescription
from mechkit.core import PointToPoint
from mechkit.sources.urdf_checks import number

NAMESPACE = "https://mechkit.dev/loop"  # `mechkit.sources.urdf.LOOP_NAMESPACE` (which imports this module)


def _point(element: ET.Element, attribute: str, where: str) -> tuple[float, float, float]:
    text = element.get(attribute, "0 0 0").split()
    if len(text) != 3:
        raise MalformedDescription(where, f"{attribute}={element.get(attribute)!r} needs three numbers (m)")
    x, y, z = (number(t, where, attribute) for t in text)
    return x, y, z


def parse_struts(root: ET.Element, frames: set[str] | None = None) -> tuple[PointToPoint, ...]:
    """The `<mechkit:strut>` elements of a URDF (see the module docstring).

    Args:
        root: the URDF's parsed `<robot>` element.
        frames: the names the frames may take (the URDF's links), or None: not checked here.

    Returns:
        The elements, in document order.

    Raises:
        MalformedDescription: a strut without a name or its frames, two of one name, a frame not among
            `frames`, a value that is not a finite number, a negative stiffness, damping or length, a
            stiffness without a length.
    """
    out: list[PointToPoint] = []
    for element in root.iter(f"{{{NAMESPACE}}}strut"):
        name = element.get("name")
        where = f"mechkit:strut {name!r}"
        a, b = element.get("frame_a"), element.get("frame_b")
        if not name or not a or not b:
            raise MalformedDescription(where, "needs a name, frame_a and frame_b")
        if name in [s.name for s in out]:
            raise MalformedDescription(where, "two struts of that name")
        for frame in (a, b):
            if frames is not None and frame not in frames:
                raise MalformedDescription(where, f"frame {frame!r} is not a link of the URDF")
        values = {
            key: number(element.get(attribute, "0"), where, attribute)
            for key, attribute in (("stiffness", "stiffness"), ("free_length", "length"), ("damping", "damping"))
        }
        values["force"] = number(element.get("force", "0"), where, "force")
        if values["stiffness"] and element.get("length") is None:
            raise MalformedDescription(where, "a stiffness needs the spring's free length (length, m)")
        try:
            out.append(
                PointToPoint(name, a, b, _point(element, "point_a", where), _point(element, "point_b", where), **values)
            )
        except InvalidParameters as err:
            raise MalformedDescription(where, str(err)) from None
    return tuple(out)
