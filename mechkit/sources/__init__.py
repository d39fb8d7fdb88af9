"""Where a mechanism comes from: a registered name or a file, read into one `Description`.

Formats (one module each): a `.urdf` with `<mechkit:loop>` elements (`urdf`), a `.urdf` with an
Extended-URDF `.yaml` sidecar beside it (`extended_urdf`), a `.xacro` / `.urdf.xacro` whose keyword
parameters become xacro arguments (`xacro_file`), an MJCF `.xml` (`mjcf`) and an SDFormat `.sdf`
(`sdf`). The URDF readers give the tree URDF with its loops as `<mechkit:loop>` elements; the MJCF
and SDFormat readers build the Pinocchio model themselves (any joint) and give its URDF only where
URDF can hold the tree.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from mechkit.base.exceptions import InvalidParameters, MalformedDescription
from mechkit.sources.description import Description
from mechkit.sources.extended_urdf import read_extended_urdf, sidecar_of
from mechkit.sources.mjcf import read_mjcf
from mechkit.sources.sdf import read_sdf
from mechkit.sources.urdf import describe_urdf, read_urdf
from mechkit.sources.xacro_file import read_xacro, xacro_args

__all__ = ["SUFFIXES", "Description", "describe_urdf", "read", "xacro_args"]

SUFFIXES = (".urdf", ".xacro", ".xml", ".sdf")


def read(path: Path, params: dict[str, Any] | None = None) -> Description:
    """The description in a file, its format told by its suffix (and a sidecar beside a URDF).

    Args:
        path: an existing file (see `resolve`).
        params: xacro arguments (only a xacro file takes any).

    Returns:
        The description.

    Raises:
        MalformedDescription: unknown suffix, unreadable, empty or invalid content.
        InvalidParameters: parameters given to a format that takes none.
    """
    params = dict(params or {})
    name = path.name
    if name.endswith(".xacro"):
        return read_xacro(path, params)
    if params:
        raise InvalidParameters(next(iter(params)), params[next(iter(params))],
                                f"{path.name} is not a xacro file: only xacro files take parameters")
    if name.endswith(".urdf"):
        sidecar = sidecar_of(path)
        return read_extended_urdf(path, sidecar) if sidecar is not None else read_urdf(path)
    if name.endswith((".xml", ".mjcf")):
        return read_mjcf(path)
    if name.endswith(".sdf"):
        return read_sdf(path)
    raise MalformedDescription(str(path), "unknown format: expected .urdf (with loops or a .yaml sidecar), "
                                          ".xacro / .urdf.xacro, MJCF .xml or SDFormat .sdf")
