"""Holding a body's pose in the world: the inputs that keep a chosen frame at a target while the base moves.

Gauss-Newton on the mechanism's own inputs, each step on the closed mechanism (the loops closed by the
core's assembly, continued from the last step's branch) with the base's root joints kept at the
carrier's pose. The residual has up to three parts: a full orientation (log3(R_target^T R), rad, in
the target's axes), a body axis kept along a world direction (the two components of R a off d: a
platform kept level), a position (m, world). Where the target has more components than the inputs
move, the step is the least-squares one and the answer says which components it cannot hold: the
directions (world axes) the frame cannot move in at the answer, with the residual left along each.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from mechkit.base import arguments
from mechkit.base.exceptions import InvalidArgument
from mechkit.bases.carrier import BASE_JOINTS
from mechkit.mechanism import Mechanism

#: A singular value below this fraction of the largest is a direction the inputs do not move.
RANK_TOL = 1e-8


@dataclass(frozen=True)
class Holding:
    """The inputs holding a frame at a target.

    Attributes:
        inputs: input joint -> value (rad or m).
        q: (nq,) the assembled configuration.
        rotation_error: rad, |log3(R_target^T R)| (nan when no orientation was asked).
        tilt: rad, the angle between R a and d (nan when no axis was asked).
        position_error: m (nan when no position was asked).
        unreachable: (what, world direction (3,), residual left along it): "rotation" (rad) or
            "position" (m) components the inputs cannot change.
        iterations: Gauss-Newton steps taken.
    """

    inputs: dict[str, float]
    q: np.ndarray
    rotation_error: float
    tilt: float
    position_error: float
    unreachable: tuple[tuple[str, np.ndarray, float], ...]
    iterations: int


def _target(rotation, axis, position) -> tuple[np.ndarray | None, tuple | None, np.ndarray | None]:
    if rotation is None and axis is None and position is None:
        raise InvalidArgument("rotation", None, "give a rotation, an axis or a position to hold")
    if rotation is not None:
        rotation = np.asarray(rotation, dtype=float)
        if rotation.shape != (3, 3) or not np.allclose(rotation.T @ rotation, np.eye(3), atol=1e-9):
            raise InvalidArgument("rotation", rotation.shape, "expected a (3, 3) rotation matrix")
    if axis is not None:
        try:
            body, world = (np.asarray(x, dtype=float) for x in axis)
        except (TypeError, ValueError):
            raise InvalidArgument("axis", axis, "expected (body axis (3,), world direction (3,))") from None
        if body.shape != (3,) or world.shape != (3,) or not (np.linalg.norm(body) > 0 and np.linalg.norm(world) > 0):
            raise InvalidArgument("axis", axis, "expected two non-zero 3-vectors: body axis, world direction")
        axis = (body / np.linalg.norm(body), world / np.linalg.norm(world))
    if position is not None:
        position = arguments.array("position", position, 3, batch=False)
    return rotation, axis, position


def _plane(d: np.ndarray) -> np.ndarray:
    """(2, 3) an orthonormal basis of the plane normal to d."""
    e1 = np.cross(d, [1.0, 0.0, 0.0] if abs(d[0]) < 0.9 else [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    return np.array([e1, np.cross(d, e1)])


def _residual(placement: pin.SE3, jacobian: np.ndarray, target) -> tuple[np.ndarray, np.ndarray, list, list]:
    """The residual rows, their Jacobian on the inputs, and what each row is (kind, world direction)."""
    rotation, axis, position = target
    rows, jac, kinds, directions = [], [], [], []
    R, omega, lin = placement.rotation, jacobian[3:], jacobian[:3]
    if rotation is not None:
        err = rotation.T @ R
        rows.append(pin.log3(err))
        jac.append(pin.Jlog3(err) @ R.T @ omega)
        kinds += ["rotation"] * 3
        directions += list(rotation.T)  # the target's axes, in world
    if axis is not None:
        body, world = axis
        plane = _plane(world)
        rows.append(plane @ (R @ body))
        jac.append(-plane @ pin.skew(R @ body) @ omega)
        kinds += ["rotation"] * 2
        directions += [np.cross(world, p) for p in plane]  # tilting about these moves R a along the plane
    if position is not None:
        rows.append(placement.translation - position)
        jac.append(lin)
        kinds += ["position"] * 3
        directions += list(np.eye(3))
    return np.concatenate(rows), np.vstack(jac), kinds, directions


def hold_pose(
    mech: Mechanism,
    frame: str,
    *,
    rotation: np.ndarray | None = None,
    axis: tuple[Sequence[float], Sequence[float]] | None = None,
    position: Sequence[float] | None = None,
    base_pose: Mapping[str, float] | None = None,
    start: Mapping[str, float] | None = None,
    tol: float = 1e-10,
    max_iter: int = 50,
) -> Holding:
    """The mechanism's inputs that hold a frame at a target in the world.

    Args:
        mech: the mechanism (on any base).
        frame: a Pinocchio frame (a link or an operational frame).
        rotation: (3, 3) target orientation in the world.
        axis: (a, d): the frame's axis a (its own axes) to keep along the world direction d (level: a = d
            = (0, 0, 1)).
        position: (3,) target position of the frame's origin (m, world).
        base_pose: root joint -> value (m, rad) of a moving base (`BASE_JOINTS`; one not named: 0).
        start: input joint -> value to start from (default: the home inputs).
        tol: stop when a step changes no input by more than this (rad or m).
        max_iter: the step cap.

    Returns:
        The `Holding`: the inputs, the configuration, the residuals and what cannot be held.

    Raises:
        InvalidArgument: an unknown frame, no target, a malformed target, base joints on a mechanism
            without them.
        ClosureNotConverged: a step's loops do not close.
    """
    if not isinstance(frame, str) or not mech.model.existFrame(frame):
        raise InvalidArgument("frame", frame, "not a frame of the mechanism")
    target = _target(rotation, axis, position)
    moving = set(BASE_JOINTS) <= set(mech.model.names)
    base = dict.fromkeys(BASE_JOINTS, 0.0) if moving else {}
    for joint, value in (base_pose or {}).items():
        if joint not in base:
            raise InvalidArgument("base_pose", joint, f"not a root joint of a moving base; they are {BASE_JOINTS}")
        base[joint] = float(value)
    home = {j: float(x) for j, x in mech.spec.home(mech.params).items() if j not in BASE_JOINTS}
    inputs = {**home, **{j: float(x) for j, x in (start or {}).items()}}
    names = list(base) + list(inputs)
    fid, data = mech.model.getFrameId(frame), mech.model.createData()
    q = mech.home_q
    for iteration in range(1, max_iter + 1):
        q = mech.assembly({**base, **inputs}, reference=q).q
        e, de, _, _ = _linearised(mech, data, fid, q, names, len(base), target)
        step = -np.linalg.lstsq(de, e, rcond=RANK_TOL)[0]
        inputs = {j: x + dx for (j, x), dx in zip(inputs.items(), step)}
        if np.abs(step).max() <= tol:
            break
    q = mech.assembly({**base, **inputs}, reference=q).q
    e, de, kinds, directions = _linearised(mech, data, fid, q, names, len(base), target)
    return Holding(inputs, q, *_errors(data.oMf[fid], target), _unreachable(e, de, kinds, directions), iteration)


def _linearised(mech: Mechanism, data: pin.Data, fid: int, q: np.ndarray, names: list, given: int, target) -> tuple:
    """The residual and its Jacobian on the inputs (the first `given` names, the base's, kept still)."""
    columns = []
    for k in range(given, len(names)):
        rates = np.zeros(len(names))
        rates[k] = 1.0
        columns.append(mech.velocities(q, rates, names))
    jac = pin.computeFrameJacobian(mech.model, data, q, fid, pin.LOCAL_WORLD_ALIGNED) @ np.array(columns).T
    pin.updateFramePlacement(mech.model, data, fid)
    return _residual(data.oMf[fid], jac, target)


def _errors(placement: pin.SE3, target) -> tuple[float, float, float]:
    rotation, axis, position = target
    nan = float("nan")
    return (
        nan if rotation is None else float(np.linalg.norm(pin.log3(rotation.T @ placement.rotation))),
        nan if axis is None else float(np.arctan2(*_sin_cos(placement.rotation @ axis[0], axis[1]))),
        nan if position is None else float(np.linalg.norm(placement.translation - position)),
    )


def _sin_cos(u: np.ndarray, d: np.ndarray) -> tuple[float, float]:
    return float(np.linalg.norm(np.cross(u, d))), float(u @ d)


def _unreachable(e: np.ndarray, de: np.ndarray, kinds: list, directions: list) -> tuple:
    """The residual space's directions the inputs do not move (left singular vectors), with what is left."""
    u, s, _ = np.linalg.svd(de)
    rank = int(np.sum(s > RANK_TOL * (s[0] if len(s) else 1.0)))
    out = []
    for column in u[:, rank:].T:
        world = sum(c * d for c, d in zip(column, directions))
        out.append((kinds[int(np.argmax(np.abs(column)))], world / np.linalg.norm(world), float(column @ e)))
    return tuple(out)
