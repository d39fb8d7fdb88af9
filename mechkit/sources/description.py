"""`Description`: what every file reader gives: the tree (a Pinocchio model, or URDF text), its loops,
couplings, springs, actuators and home."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import pinocchio as pin

from mechkit.base.exceptions import MalformedDescription
from mechkit.core import Actuator, Coupling, JointSpring, LoopClosure
from mechkit.sources.closure_elements import ClosureElement


@dataclass(frozen=True)
class Description:
    """A mechanism as read from a file.

    Attributes:
        name: a name for reports (the file's stem, or the model name it declares).
        urdf: the tree URDF text with `<mechkit:loop>` (and `<mechkit:home>`) elements, or None where
            the format has no URDF of the tree (its joints need not be URDF's: ball, free-flyer).
        actuated: the actuators' names, in effort order: a joint's name (a motor on that joint) or
            the name of one of `actuators`; empty when the file declares none (unactuated).
        home: joint -> value of the default assembly's inputs (rad or m; a ball joint's rotation
            vector (3,), a free-flyer's position and rotation vector (6,)).
        guess: joint -> value near which the default assembly is sought (picks the branch).
        pose: what `guess` is, named by the assembly's branch ("the keyframe 'home'", "qpos0").
        source: the file read; `format`: "urdf", "extended-urdf", "xacro", "mjcf", "sdf", "urdf+".
        params: the xacro arguments and the values used (strings; defaults included), empty for
            other formats.
        closures: the loops, when the reader has parsed them (else None: parsed from `urdf` on use).
        model: the tree as a Pinocchio model, when the reader built it (else built from `urdf`).
        couplings: coupling rows between joints (mimic, gearbox, joint and tendon equalities).
        springs: joint springs and dampers.
        actuators: the actuators that are not one joint's motor (tendon transmissions), by name.
        ignored_closures: another tool's loop closures in the file, left out as asked
            (`mechkit.sources.read`, ignore_unknown_closures).
        source_urdf: the URDF a reduced description comes from (`mechkit.reduction`), whose elements that
            name links and joints (beams, elastic joints) still apply; None otherwise.
    """

    name: str
    urdf: str | None
    actuated: tuple[str, ...]
    home: dict[str, float | tuple[float, ...]] = field(default_factory=dict)
    guess: dict[str, float | tuple[float, ...]] = field(default_factory=dict)
    source: Path | None = None
    format: str = "urdf"
    params: dict[str, str] = field(default_factory=dict)
    closures: tuple[LoopClosure, ...] | None = None
    model: pin.Model | None = None
    couplings: tuple[Coupling, ...] = ()
    springs: tuple[JointSpring, ...] = ()
    actuators: tuple[Actuator, ...] = ()
    ignored_closures: tuple[ClosureElement, ...] = ()
    source_urdf: str | None = None
    pose: str = "the joints' zero"


def read_text(path: Path) -> str:
    """A description file's text.

    Args:
        path: the file.

    Returns:
        Its text.

    Raises:
        MalformedDescription: the file cannot be read, or is empty.
    """
    try:
        text = path.read_text()
    except (OSError, UnicodeDecodeError) as err:
        raise MalformedDescription(str(path), f"cannot read it: {err}") from None
    if not text.strip():
        raise MalformedDescription(str(path), "the file is empty")
    return text
