"""`Description`: what every file reader gives — the tree URDF with its loops, actuators and home."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from mechkit.base.exceptions import MalformedDescription
from mechkit.core.records import LoopClosure


@dataclass(frozen=True)
class Description:
    """A mechanism as read from a file.

    Attributes:
        name: a name for reports (the file's stem, or the model name it declares).
        urdf: the tree URDF text with `<mechkit:loop>` (and `<mechkit:home>`) elements.
        actuated: actuated joint names the file declares (URDF `<transmission>`, sidecar `name_mot`,
            MJCF actuators); empty when it declares none (the mechanism is then unactuated).
        home: joint -> value (rad or m) of the default assembly's inputs.
        guess: joint -> value near which the default assembly is sought (picks the branch).
        source: the file read; `format`: "urdf", "extended-urdf", "xacro" or "mjcf".
        params: the xacro arguments and the values used (strings; defaults included), empty for
            other formats.
        closures: the loops of `urdf`, when the reader has parsed them (else None: parsed on use).
    """

    name: str
    urdf: str
    actuated: tuple[str, ...]
    home: dict[str, float] = field(default_factory=dict)
    guess: dict[str, float] = field(default_factory=dict)
    source: Path | None = None
    format: str = "urdf"
    params: dict[str, str] = field(default_factory=dict)
    closures: tuple[LoopClosure, ...] | None = None


def read_text(path: Path) -> str:
    """A description file's text; unreadable or empty is a `MalformedDescription`."""
    try:
        text = path.read_text()
    except (OSError, UnicodeDecodeError) as err:
        raise MalformedDescription(str(path), f"cannot read it: {err}") from None
    if not text.strip():
        raise MalformedDescription(str(path), "the file is empty")
    return text
