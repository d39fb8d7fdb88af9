"""Closure records: what the core takes besides a Pinocchio model, from any source.

A `LoopClosure` names a cut joint between two Pinocchio frames (of any kind: a link's, a joint's, an
operational frame) whose origins coincide when the loop is closed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

LOOP_KINDS = ("revolute", "prismatic", "spherical", "hooke", "weld")
ROW_SETS = ("spatial", "planar", "spherical")


@dataclass(frozen=True)
class LoopClosure:
    """One loop closure: the cut joint between two frames whose origins coincide when closed.

    Attributes:
        name: the cut joint's name (a joint of the mechanism, e.g. "C").
        kind: revolute, prismatic, spherical, hooke or weld.
        frame_a: frame on the "parent" side of the cut.
        frame_b: frame on the "child" side.
        axis: unit joint axis in frame_a's frame (revolute, prismatic; the plane normal of planar
            rows of other kinds), else None.
        axis_a: Hooke: first cross axis, in frame_a's frame.
        axis_b: Hooke: second cross axis, in frame_b's frame.
        rows: which constraint rows the scene keeps: "spatial", "planar" or "spherical".
        explicit_rows: whether the declaration names its rows (else the structure analysis may
            choose minimal rows, `mechkit.core.structure`).
    """

    name: str
    kind: str
    frame_a: str
    frame_b: str
    axis: np.ndarray | None = None
    axis_a: np.ndarray | None = None
    axis_b: np.ndarray | None = None
    rows: str = "spatial"
    explicit_rows: bool = True
