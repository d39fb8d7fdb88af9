"""Closure records: what the core takes besides a Pinocchio model, from any source.

A `LoopClosure` names a cut joint between two Pinocchio frames (of any kind: a link's, a joint's, an
operational frame) whose origins coincide when the loop is closed. A `PointToPoint` is a spring, damper
and force between two body points (`mechkit.forces.point_to_point` applies it).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from mechkit.base.arguments import LARGEST
from mechkit.base.exceptions import InvalidParameters

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


@dataclass(frozen=True)
class Coupling:
    """A coupling row between one-freedom joints (URDF `mimic`, MuJoCo joint and tendon equalities,
    SDFormat `gearbox`): x_f - follower_ref = P(x_l - leader_ref), P(s) = sum_k polynomial[k] s^k.

    x_f = sum of coefficient * value over `follower`, x_l the same over `leader` (rad or m; a
    continuous joint's value is its angle). With no leader, the row fixes x_f to follower_ref +
    polynomial[0].

    Attributes:
        name: the coupling's name (for reports and errors).
        follower: ((joint, coefficient), ...), at least one term.
        leader: ((joint, coefficient), ...), possibly empty.
        polynomial: (c0, c1, ...) coefficients of P (a URDF mimic: (offset, multiplier)).
        follower_ref, leader_ref: reference values of x_f and x_l (MuJoCo's qpos0 terms; 0 elsewhere).
    """

    name: str
    follower: tuple[tuple[str, float], ...]
    leader: tuple[tuple[str, float], ...] = ()
    polynomial: tuple[float, ...] = (0.0, 1.0)
    follower_ref: float = 0.0
    leader_ref: float = 0.0


@dataclass(frozen=True)
class JointSpring:
    """A spring and damper on a one-freedom joint: effort = preload - stiffness (x - reference) - damping dx/dt.
    On a joint of several freedoms (ball, free-flyer: MuJoCo's damping) only the damper: effort =
    -damping v on each of its velocity coordinates (stiffness, reference and preload 0).

    Attributes:
        joint: the joint's name.
        stiffness: N m/rad (revolute) or N/m (prismatic), >= 0.
        reference: the spring's reference value of x (rad or m).
        preload: effort at x = reference (N m or N).
        damping: N m s/rad or N s/m, >= 0.
    """

    joint: str
    stiffness: float = 0.0
    reference: float = 0.0
    preload: float = 0.0
    damping: float = 0.0

    def __post_init__(self) -> None:
        """Refuse, naming the joint, a value no spring has: NaN, inf or beyond `LARGEST`, a negative stiffness or
        damping."""
        values = {"stiffness": self.stiffness, "reference": self.reference, "preload": self.preload}
        values["damping"] = self.damping
        for name, value in values.items():
            if not abs(value) <= LARGEST or (name in ("stiffness", "damping") and value < 0):
                raise InvalidParameters(
                    f"spring {name} of {self.joint!r}",
                    value,
                    f"must be finite, at most {LARGEST:g} in size"
                    + (" and >= 0" if name in ("stiffness", "damping") else ""),
                )


@dataclass(frozen=True)
class Actuator:
    """One actuator: its effort u acts on the joints as the generalised force coefficient * u on each
    named one-freedom joint (a joint motor: one term of coefficient 1; a tendon motor: the tendon's
    joint coefficients, MuJoCo's `gear` included).

    Attributes:
        name: the actuator's name (a joint motor is named after its joint).
        joints: ((joint, coefficient), ...), at least one term.
    """

    name: str
    joints: tuple[tuple[str, float], ...]


Law = Callable[[float, float, float], float]
"""(length m, rate m/s, t s) -> force along the line (N, positive pushes the points apart)."""


@dataclass(frozen=True)
class PointToPoint:
    """A spring, damper and force between two body points (see the module docstring).

    Attributes:
        name: the element's name.
        frame_a: the frame (a link, a site, a joint's frame) point a is fixed in.
        frame_b: the frame point b is fixed in.
        point_a: (3,) point a in frame_a (m).
        point_b: (3,) point b in frame_b (m).
        stiffness: N/m, >= 0.
        free_length: the spring's length at rest (m, >= 0).
        damping: N s/m, >= 0.
        force: a constant force along the line (N, positive pushes apart: a gas spring's).
        law: a force law (length, rate, t) -> N (positive pushes apart), or None.
    """

    name: str
    frame_a: str
    frame_b: str
    point_a: tuple[float, float, float] = (0.0, 0.0, 0.0)
    point_b: tuple[float, float, float] = (0.0, 0.0, 0.0)
    stiffness: float = 0.0
    free_length: float = 0.0
    damping: float = 0.0
    force: float = 0.0
    law: Law | None = None

    def __post_init__(self) -> None:
        """Refuse, naming the element, a value no strut has: non-finite numbers, negative stiffness,
        damping or length, points not of three numbers, a law that is not callable."""
        where = f"point-to-point {self.name!r}"
        for attribute in ("stiffness", "free_length", "damping", "force"):
            value = getattr(self, attribute)
            if not isinstance(value, (int, float)) or not math.isfinite(value):
                raise InvalidParameters(f"{where} {attribute}", value, "must be a finite number")
            if attribute != "force" and value < 0:
                raise InvalidParameters(f"{where} {attribute}", value, "must be >= 0")
        for attribute in ("point_a", "point_b"):
            p = np.asarray(getattr(self, attribute), dtype=float)
            if p.shape != (3,) or not np.all(np.isfinite(p)):
                raise InvalidParameters(
                    f"{where} {attribute}", getattr(self, attribute), "needs three finite numbers (m)"
                )
        if self.law is not None and not callable(self.law):
            raise InvalidParameters(f"{where} law", self.law, "must be a function (length, rate, t) -> force")
        if self.law is not None and self.damping:
            raise InvalidParameters(
                f"{where} law", self.law, "a law and a damper in one element: give the damper as its own element"
            )
