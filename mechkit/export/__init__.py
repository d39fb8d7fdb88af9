"""Export a mechanism: mechkit's own URDF (`urdf`), MJCF (MuJoCo, `mjcf`), Extended URDF (`extended_urdf`) and
URDF+ (`urdf_plus`)."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from mechkit.base.exceptions import OutputError, UnknownOption
from mechkit.export.extended_urdf import frame_b_vector, to_extended_urdf
from mechkit.export.mjcf import body_name, to_mjcf
from mechkit.export.urdf import to_urdf
from mechkit.export.urdf_plus import to_urdf_plus

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

__all__ = [
    "FORMATS",
    "body_name",
    "export_command",
    "frame_b_vector",
    "sidecar_path",
    "to_extended_urdf",
    "to_mjcf",
    "to_urdf_plus",
]

FORMATS = ("urdf", "mjcf", "extended-urdf", "urdf-plus", "urdf+")


def export_command(mechanism: Mechanism, fmt: str, output: str | Path) -> list[Path]:
    """Write the mechanism in `fmt` (`FORMATS`: "urdf", "mjcf", "extended-urdf", "urdf-plus" alias "urdf+") to
    `output`; returns the files written.

    extended-urdf also writes the YAML sidecar beside the URDF (same stem, `.yaml`); both files are
    written as one step (neither is replaced unless both can be written). The others to `-` write to
    standard output.

    Args:
        mechanism: the mechanism.
        fmt: one of `FORMATS`.
        output: the file (the URDF for extended-urdf), or `-` (standard output) for mjcf and urdf+.

    Returns:
        The files written.

    Raises:
        UnknownOption: an unknown format.
        MethodUnavailable: a joint, cut, coupling or actuator the format cannot express.
        OutputError: the output is refused (a directory, a device, the sidecar's own name, ...) or
            cannot be written.
    """
    from mechkit.base.atomic import write_files, write_text

    if fmt not in FORMATS:
        raise UnknownOption("format", fmt, FORMATS)
    if fmt == "mjcf":
        return [write_text(output, to_mjcf(mechanism))]
    if fmt in ("urdf-plus", "urdf+"):
        return [write_text(output, to_urdf_plus(mechanism))]
    if fmt == "urdf":
        return [write_text(output, to_urdf(mechanism))]
    sidecar = sidecar_path(output)
    if Path(output) == sidecar:
        raise OutputError(
            output, "the Extended URDF needs a name whose .yaml sidecar is another file (e.g. robot.urdf)"
        )
    urdf, sidecar_text = to_extended_urdf(mechanism)
    return write_files({output: urdf.encode(), sidecar: sidecar_text.encode()})


def sidecar_path(output: str | Path) -> Path:
    """The YAML sidecar an Extended-URDF export writes beside its URDF.

    Args:
        output: the URDF's file.

    Returns:
        The same name with the suffix `.yaml`.
    """
    return Path(output).with_suffix(".yaml")
