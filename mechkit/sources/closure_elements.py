"""Elements of other tools that close a loop or couple joints, which no mechkit reader turns into a closure:
found with their file and line, so that a description never loads as an open tree of the wrong mobility in
silence. The loader refuses a file holding any (`refusal`), or, asked to ignore them, warns once per element
with the mobility the model is left with (`mechkit.loading`).

`RULES` is the list: an element another tool reads as a loop closure or a coupling (Drake's constraints
other than the ball constraint, an SDFormat file's Drake joints). The day a reader turns
one into a closure, its rule goes (one change). What mechkit reads itself (`<mechkit:loop>`, `<mimic>`,
URDF+ `<loop>`/`<coupling>`, the Extended-URDF sidecar, SDFormat's joint graph, MJCF's equalities and
tendons, whose unknown kinds the MJCF reader refuses by name, Drake's ball constraints and bushings, a URDF's
Gazebo joints, `mechkit.sources.drake_elements`, and its Drake joints,
`mechkit.sources.drake_joints`) is not listed; an element that cannot
change the kinematics (Drake's collision properties, Gazebo's materials, plugins) is ignored as before.
"""

from __future__ import annotations

import xml.parsers.expat
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

from mechkit.base.exceptions import MalformedDescription

#: Drake's XML namespace (its URDF and SDFormat extensions, `xmlns:drake="http://drake.mit.edu"`).
DRAKE = "http://drake.mit.edu"


@dataclass(frozen=True)
class Rule:
    """A kind of element that closes a loop or couples joints in another tool.

    Attributes:
        matches: (namespace URI, local name, parent's local name) -> whether an element is of this kind.
        meaning: what the element does in its tool, in words.
    """

    matches: Callable[[str, str, str], bool]
    meaning: str


RULES = (
    Rule(
        lambda uri, local, parent: (
            uri == DRAKE and local.endswith("_constraint") and local != "ball_constraint"
        ),  # the ball constraint is read (mechkit.sources.drake_elements)
        "a Drake constraint, which closes a loop in Drake",
    ),
    Rule(
        lambda uri, local, parent: uri == DRAKE and local == "joint" and parent == "model",
        "a Drake joint in SDFormat (a URDF's is read: mechkit.sources.drake_joints)",
    ),
)


@dataclass(frozen=True)
class ClosureElement:
    """One element of a description that closes a loop or couples joints in another tool, unread.

    Attributes:
        element: as written, with its prefix (e.g. "drake:ball_constraint", "gazebo/joint").
        file: the file it is in.
        line: its line there.
        meaning: what it does in its tool.
    """

    element: str
    file: Path
    line: int
    meaning: str

    def __str__(self) -> str:
        """`file:line: <element> (meaning)`."""
        return f"{self.file.name}:{self.line}: <{self.element}> ({self.meaning})"


def unread_closures(files: Sequence[Path]) -> list[ClosureElement]:
    """The elements of `RULES` in the description's files, in file and document order; an element nested
    in a found one is part of it.

    Args:
        files: the description's files (`mechkit.sources.input_files.description_files`); files that are
            not XML (a YAML sidecar) or not well-formed are skipped (their reader refuses those).

    Returns:
        The elements found.
    """
    found: list[ClosureElement] = []
    for path in files:
        if path.suffix in (".urdf", ".xacro", ".sdf", ".xml", ".mjcf"):
            found.extend(_scan(path))
    return found


def refusal(found: Sequence[ClosureElement]) -> MalformedDescription:
    """The error for a description holding elements mechkit does not read as closures.

    Args:
        found: what `unread_closures` found (not empty).

    Returns:
        A `MalformedDescription` naming the first, how many there are, and what to do.
    """
    first = found[0]
    more = f" and {len(found) - 1} more such element(s)" if len(found) > 1 else ""
    return MalformedDescription(
        str(first),
        f"mechkit does not read this element{more}, and without it the loop it closes would silently stay "
        "open: declare the closure as <mechkit:loop> (docs/your_own_mechanism.md), or load with "
        "--ignore-unknown-closures (ignore_unknown_closures=True) to accept the open tree",
    )


def _scan(path: Path) -> list[ClosureElement]:
    """The elements of `RULES` in one XML file, each with its line (expat, namespaces resolved)."""
    found: list[ClosureElement] = []
    stack: list[tuple[str, str, bool]] = []  # (uri, local, inside a found element)
    parser = xml.parsers.expat.ParserCreate(namespace_separator="}")

    def start(tag: str, _attrs: dict) -> None:
        uri, _, local = tag.rpartition("}")
        parent_local = stack[-1][1] if stack else ""
        inside = bool(stack) and stack[-1][2]
        rule = None if inside else next((r for r in RULES if r.matches(uri, local, parent_local)), None)
        if rule is not None:
            name = f"drake:{local}" if uri == DRAKE else f"{parent_local}/{local}" if parent_local else local
            found.append(ClosureElement(name, path, parser.CurrentLineNumber, rule.meaning))
        stack.append((uri, local, inside or rule is not None))

    parser.StartElementHandler = start
    parser.EndElementHandler = lambda _tag: stack.pop()
    try:
        parser.Parse(path.read_bytes(), True)
    except (xml.parsers.expat.ExpatError, OSError):
        return found  # not XML, or not well-formed: its reader says so
    return found
