"""Export a mechanism for other tools: MJCF (MuJoCo, `mjcf`) and Extended URDF (`extended_urdf`)."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from mechkit.exceptions import InvalidParameters
from mechkit.export.extended_urdf import frame_b_vector, to_extended_urdf
from mechkit.export.mjcf import body_name, to_mjcf
from mechkit.sources.extended_urdf import load_extended_urdf

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

__all__ = ["FORMATS", "body_name", "export_command", "frame_b_vector", "load_extended_urdf", "to_extended_urdf",
           "to_mjcf"]

FORMATS = ("mjcf", "extended-urdf")


def export_command(mechanism: Mechanism, fmt: str, output: str | Path) -> list[Path]:
    """Write the mechanism in `fmt` ("mjcf" or "extended-urdf") to `output`; returns the files written.

    extended-urdf also writes the YAML sidecar beside the URDF (same stem, `.yaml`).

    Raises:
        InvalidParameters: an unknown format.
        MethodUnavailable: a joint or cut the format cannot express.
    """
    from mechkit.atomic import write_text

    output = Path(output)
    if fmt == "mjcf":
        write_text(output, to_mjcf(mechanism))
        return [output]
    if fmt == "extended-urdf":
        urdf, sidecar_text = to_extended_urdf(mechanism)
        sidecar = output.with_suffix(".yaml")
        write_text(output, urdf)
        write_text(sidecar, sidecar_text)
        return [output, sidecar]
    raise InvalidParameters("format", fmt, f"expected one of {FORMATS}")
