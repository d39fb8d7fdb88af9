"""A `.xacro` / `.urdf.xacro` file: keyword parameters become xacro arguments, then it is a URDF."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from mechkit.description import parse_xml, render_urdf
from mechkit.exceptions import InvalidParameters
from mechkit.sources.description import Description, read_text
from mechkit.sources.urdf import describe_urdf

XACRO_NAMESPACE = "http://www.ros.org/wiki/xacro"


def read_xacro(path: Path, params: dict[str, Any]) -> Description:
    """Run xacro with `params` as arguments (numbers written with `repr`), then read the URDF.

    Raises:
        InvalidParameters: a parameter the file declares no `<xacro:arg>` for.
        MalformedDescription: not XML, xacro fails, or the URDF is invalid.
    """
    declared = xacro_args(path)
    for key, value in params.items():
        if key not in declared:
            raise InvalidParameters(key, value, f"{path.name} declares no such xacro:arg; it has {sorted(declared)}")
    args = {k: _arg(v) for k, v in params.items()}
    urdf = render_urdf(path.resolve(), args)
    used = {k: v for k, v in declared.items() if v is not None} | args
    return describe_urdf(urdf, path, "xacro", used)


def xacro_args(path: Path) -> dict[str, str | None]:
    """The `<xacro:arg name default>` a xacro file declares (name -> default, None without one)."""
    root = parse_xml(read_text(path), str(path))
    return {a.get("name"): a.get("default") for a in root.iter(f"{{{XACRO_NAMESPACE}}}arg")}


def _arg(value: Any) -> str:
    return repr(float(value)) if isinstance(value, (int, float)) and not isinstance(value, bool) else str(value)
