"""Which constraint rows each loop closure keeps, in its own frames.

Every cut row is one of two exact forms (`mechkit.core.kernel` evaluates them):

- a position row   e = t . (p_b - p_a), t a unit vector fixed in frame_a;
- an alignment row e = u . w, u fixed in frame_a, w fixed in frame_b (perpendicular when closed).

Rows kept per closure kind and row set (`LoopClosure.rows`):

| kind | spatial | planar (axis normal to the plane) | spherical (axis through a common centre) |
|---|---|---|---|
| revolute | 3 position + 2 alignment = 5 | 2 position normal to the axis | 2 alignment |
| spherical | 3 position | 2 position normal to `axis` | - |
| hooke | 3 position + 1 alignment (axis_a . axis_b) | - | 1 alignment |
| weld | 6 | 2 position + 1 alignment | 3 alignment |
| prismatic | 2 position normal to the axis + 3 alignment | - | - |

A coupling keeps one row on joint values (`mechkit.core.records.Coupling`), resolved on a model by
`mechkit.core.coupling_rows`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import MalformedDescription
from mechkit.base.spatial import cross
from mechkit.core.records import LoopClosure


def perpendicular_pair(n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit vectors completing a unit vector to a right-handed orthonormal frame.

    Args:
        n: (3,) unit vector.

    Returns:
        (t1, t2), each (3,), unit, with (t1, t2, n) right-handed and orthonormal.
    """
    helper = np.array([1.0, 0, 0]) if abs(n[0]) < 0.9 else np.array([0, 1.0, 0])
    t1 = cross(n, helper)
    t1 /= np.linalg.norm(t1)
    return t1, cross(n, t1)


@dataclass(frozen=True)
class CutRows:
    """The rows one closure keeps, in its frames' coordinates.

    Attributes:
        closure: the declaration.
        frame_a, frame_b: Pinocchio frame ids.
        positions: (3, k) position-row directions t, in frame_a.
        alignments: ((u in frame_a, w in frame_b), ...) alignment rows.
    """

    closure: LoopClosure
    frame_a: int
    frame_b: int
    positions: np.ndarray
    alignments: tuple[tuple[np.ndarray, np.ndarray], ...]

    @property
    def size(self) -> int:
        """Number of rows the cut keeps (position rows + alignment rows)."""
        return self.positions.shape[1] + len(self.alignments)


def frame_id(model: pin.Model, closure: LoopClosure, frame: str) -> int:
    """The Pinocchio id of a closure's frame (any frame type).

    Args:
        model: the Pinocchio model.
        closure: the closure naming the frame (for the error message).
        frame: the frame's name.

    Returns:
        The frame's id in `model.frames`.

    Raises:
        MalformedDescription: no frame of that name.
    """
    if not model.existFrame(frame):
        raise MalformedDescription(f"loop {closure.name!r}", f"frame {frame!r} not in the model")
    return model.getFrameId(frame)


def cut_rows(model: pin.Model, closure: LoopClosure, rows: str | None = None) -> CutRows:
    """The rows a closure keeps, in its frames' coordinates.

    Args:
        model: the Pinocchio model holding the closure's frames.
        closure: the loop closure.
        rows: the row set ("spatial", "planar" or "spherical"); None: the closure's own `rows`.

    Returns:
        The cut's frame ids, position-row directions (3, k) in frame_a and alignment-row vector pairs.

    Raises:
        MalformedDescription: a frame not in the model, or a prismatic cut with rows other than "spatial".
    """
    rows = rows or closure.rows
    ids = [frame_id(model, closure, f) for f in (closure.frame_a, closure.frame_b)]
    eye = np.eye(3)
    kind, n = closure.kind, closure.axis
    t1, t2 = perpendicular_pair(n) if n is not None else (None, None)
    frame_fixed = [(eye[1], eye[2]), (eye[2], eye[0]), (eye[0], eye[1])]  # relative rotation locked
    positions: list[np.ndarray] = []
    alignments: list[tuple[np.ndarray, np.ndarray]] = []
    if kind == "revolute":
        if rows in ("spatial", "planar"):
            positions = list(eye) if rows == "spatial" else [t1, t2]
        if rows in ("spatial", "spherical"):
            alignments = [(t1, n), (t2, n)]
    elif kind == "spherical":
        positions = list(eye) if rows == "spatial" else [t1, t2]
    elif kind == "hooke":
        positions = list(eye) if rows == "spatial" else []
        alignments = [(closure.axis_a, closure.axis_b)]
    elif kind == "weld":
        if rows == "spatial":
            positions, alignments = list(eye), frame_fixed
        elif rows == "planar":
            positions, alignments = [t1, t2], [(t1, t2)]
        else:
            alignments = frame_fixed
    elif kind == "prismatic":
        if rows != "spatial":
            raise MalformedDescription(f"loop {closure.name!r}", "a prismatic cut supports rows='spatial' only")
        positions, alignments = [t1, t2], frame_fixed
    pos = np.array(positions).T if positions else np.zeros((3, 0))
    return CutRows(closure, ids[0], ids[1], pos, tuple(alignments))
