"""Where a mechanism comes from: a registered name or a file, read into one `Description`.

Formats (one module each): a `.urdf` with `<mechkit:loop>` elements (`urdf`), a `.urdf` with an
Extended-URDF `.yaml` sidecar beside it (`extended_urdf`), a `.urdf` with URDF+ `<loop>` /
`<coupling>` elements (`urdf_plus`), a `.xacro` / `.urdf.xacro` whose keyword parameters become xacro
arguments (`xacro_file`), an MJCF `.xml` (`mjcf`) and an SDFormat `.sdf` (`sdf`). Every reader gives a
`Description`: the tree (URDF text, or a Pinocchio model where it has joints URDF lacks), its loops as
`LoopClosure` records, its couplings, springs and actuators.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

from mechkit.base.exceptions import InvalidArgument, InvalidParameters, MalformedDescription
from mechkit.sources.closure_elements import ClosureElement, refusal, unread_closures
from mechkit.sources.description import Description, read_text
from mechkit.sources.extended_urdf import read_extended_urdf, sidecar_of
from mechkit.sources.input_files import description_files
from mechkit.sources.mjcf import read_mjcf
from mechkit.sources.sdf import read_sdf
from mechkit.sources.urdf import describe_urdf, parse_xml, read_urdf
from mechkit.sources.urdf_plus import is_urdf_plus, read_urdf_plus
from mechkit.sources.xacro_file import read_xacro, xacro_args

__all__ = ["SUFFIXES", "ClosureElement", "Description", "describe_urdf", "read", "xacro_args"]

SUFFIXES = (".urdf", ".xacro", ".xml", ".sdf")


def read(
    path: Path, params: dict[str, Any] | None = None, freeflyer: bool = False, ignore_unknown_closures: bool = False
) -> Description:
    """The description in a file, its format told by its suffix (and, for a URDF, a sidecar beside it or
    URDF+ constraints in it).

    Args:
        path: an existing file (see `resolve`).
        params: xacro arguments (only a xacro file takes any).
        freeflyer: put an Extended-URDF file's tree on a free-flyer root (`read_extended_urdf`).
        ignore_unknown_closures: read a file holding another tool's loop closures mechkit does not read
            (`mechkit.sources.closure_elements`) as the tree without them; they are listed in the
            description's `ignored_closures`.

    Returns:
        The description.

    Raises:
        MalformedDescription: unknown suffix, unreadable, empty or invalid content; an element that closes
            a loop in another tool and that mechkit does not read, unless `ignore_unknown_closures`.
        InvalidParameters: parameters given to a format that takes none; InvalidArgument: `freeflyer`
            for a file that is not Extended URDF.
    """
    unread = unread_closures(description_files(path))
    if unread and not ignore_unknown_closures:
        raise refusal(unread)
    description = _read_format(path, params, freeflyer)
    return dataclasses.replace(description, ignored_closures=tuple(unread)) if unread else description


def _read_format(path: Path, params: dict[str, Any] | None, freeflyer: bool) -> Description:
    """The reader of the file's format (see `read`)."""
    params = dict(params or {})
    name = path.name
    if freeflyer and not (name.endswith(".urdf") and sidecar_of(path) is not None):
        raise InvalidArgument(
            "freeflyer",
            freeflyer,
            f"{name} is not an Extended-URDF file (a .urdf with a .yaml "
            "sidecar): only those take a free-flyer root (MJCF and SDFormat declare their own "
            "free joints)",
        )
    if name.endswith(".xacro"):
        return read_xacro(path, params)
    if params:
        raise InvalidParameters(
            next(iter(params)),
            params[next(iter(params))],
            f"{path.name} is not a xacro file: only xacro files take parameters",
        )
    if name.endswith(".urdf"):
        sidecar = sidecar_of(path)
        if is_urdf_plus(parse_xml(read_text(path), str(path))):
            if sidecar is not None:
                raise MalformedDescription(
                    str(path),
                    f"declares URDF+ loops or couplings and has an Extended-URDF "
                    f"sidecar {sidecar.name}: one loop convention per file",
                )
            return read_urdf_plus(path)
        return read_extended_urdf(path, sidecar, freeflyer) if sidecar is not None else read_urdf(path)
    if name.endswith((".xml", ".mjcf")):
        return read_mjcf(path)
    if name.endswith(".sdf"):
        return read_sdf(path)
    raise MalformedDescription(
        str(path),
        "unknown format: expected .urdf (with loops, URDF+ constraints or a .yaml "
        "sidecar), .xacro / .urdf.xacro, MJCF .xml or SDFormat .sdf",
    )
