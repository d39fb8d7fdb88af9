"""Where a mechanism comes from: a registered name or a file, read into one `Description`.

Formats (one module each): a `.urdf` with `<mechkit:loop>` elements (`urdf`), a `.urdf` with an
Extended-URDF `.yaml` sidecar beside it (`extended_urdf`), a `.xacro` / `.urdf.xacro` whose keyword
parameters become xacro arguments (`xacro_file`), and an MJCF `.xml` (`mjcf`). Every reader gives
the tree URDF with its loops as `<mechkit:loop>` elements, so the rest of mechkit reads one format.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from mechkit.exceptions import InvalidParameters, MalformedDescription
from mechkit.registry import names
from mechkit.sources.description import Description
from mechkit.sources.extended_urdf import read_extended_urdf, sidecar_of
from mechkit.sources.mjcf import read_mjcf
from mechkit.sources.urdf import describe_urdf, read_urdf
from mechkit.sources.xacro_file import read_xacro, xacro_args

__all__ = ["Description", "describe_urdf", "read", "resolve", "xacro_args"]

SUFFIXES = (".urdf", ".xacro", ".xml")


def resolve(source: str | Path) -> str | Path:
    """A registered name (returned as `str`) or an existing description file (returned as `Path`).

    A string is a name when it is registered; otherwise, or when it is a `Path` or looks like a path
    (a separator or a known suffix), it must be a readable file.

    Raises:
        InvalidParameters: neither a registered name nor a path (the message lists the names).
        MalformedDescription: the path does not exist or is a directory.
    """
    if isinstance(source, str) and source in names():
        return source
    text = str(source)
    looks_like_path = isinstance(source, Path) or "/" in text or "\\" in text or text.endswith(SUFFIXES)
    if not looks_like_path:
        raise InvalidParameters("source", text, f"no such mechanism and not a path; registered: {', '.join(names())}")
    path = Path(text).expanduser()
    if not path.exists():
        raise MalformedDescription(text, "no such file")
    if path.is_dir():
        raise MalformedDescription(text, "is a directory, not a description file")
    return path


def read(path: Path, params: dict[str, Any] | None = None) -> Description:
    """The description in a file, its format told by its suffix (and a sidecar beside a URDF).

    Args:
        path: an existing file (see `resolve`).
        params: xacro arguments (only a xacro file takes any).

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
    raise MalformedDescription(str(path), "unknown format: expected .urdf (with loops or a .yaml sidecar), "
                                          ".xacro / .urdf.xacro or MJCF .xml")
