"""Scenes: named motions of a mechanism as assembled configurations, and the generic input sweep.

A mechanism's spec declares its own scenes (`MechanismSpec.scenes`: name -> function returning the
configurations q along the motion, in order). Every mechanism also gets a generic "sweep" (unless it
declares its own): each actuated input in turn swings about its home value and back while the others
stay at home, assembled with warm starts; an excursion stops at its first pose that does not
assemble, with a `SweepStopped` warning saying where and why, and the sweep goes on with the next one.
Pictures (`mechkit.viz`), benchmarks and motion studies read scenes from here.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import InvalidParameters, MalformedDescription, MechkitError
from mechkit.catalog.contract import SceneFunction
from mechkit.mechanism import Mechanism

CLOSURE_TOL = 1e-6  # largest closure residual accepted in a scene's pose (m, or rad-like rows)
SWEEP_FRAMES = 40  # frames per swept input
SWEEP_ANGLE = 0.3  # rad, swing of a revolute input
SWEEP_STROKE = 0.05  # fraction of the mechanism's size, swing of a prismatic input
SCENE_STEP = 1.0  # s between the poses of a scene without a time axis (ours)


class SweepStopped(UserWarning):
    """The generic sweep stopped early: a pose did not assemble (the message says which and why)."""


def joint_extent(model: pin.Model, data: pin.Data, q: np.ndarray) -> float:
    """Largest extent (m) of the joint origins at q along a world axis (at least 1 mm).

    Args:
        model: the Pinocchio model.
        data: a data of it (its placements overwritten).
        q: a configuration (nq,).

    Returns:
        The extent (m).
    """
    pin.forwardKinematics(model, data, q)
    pts = np.array([data.oMi[j].translation for j in range(model.njoints)])
    return max(float(np.max(np.ptp(pts, axis=0))), 1e-3)


def scenes(mechanism: Mechanism) -> dict[str, SceneFunction]:
    """The mechanism's scenes: those its spec declares, plus the generic "sweep" unless it has its own.

    Args:
        mechanism: the mechanism.

    Returns:
        Scene name -> the function giving its poses, the spec's first in order.
    """
    found = dict(mechanism.spec.scenes)
    found.setdefault("sweep", sweep)
    return found


def scene_poses(mechanism: Mechanism, name: str) -> list[np.ndarray]:
    """The configurations of a scene, checked: at least 2, each of size nq, finite, loops closed.

    Args:
        mechanism: the mechanism.
        name: one of its scenes (`scenes`).

    Returns:
        The assembled configurations, each (nq,).

    Raises:
        InvalidParameters: no scene of that name.
        MalformedDescription: the scene returned a pose that is not an assembled configuration.
    """
    known = scenes(mechanism)
    if name not in known:
        raise InvalidParameters("scene", name, f"{mechanism.spec.name} has the scenes {', '.join(known)}")
    where = f"{mechanism.spec.name} scene {name!r}"
    poses = [np.asarray(q, dtype=float) for q in known[name](mechanism)]
    if len(poses) < 2:
        raise MalformedDescription(where, f"needs at least 2 poses, got {len(poses)}")
    for i, q in enumerate(poses):
        if q.shape != (mechanism.model.nq,) or not np.all(np.isfinite(q)):
            raise MalformedDescription(where, f"pose {i} is not a finite vector of size nq={mechanism.model.nq}")
        residual = float(np.max(np.abs(mechanism.closure_residual(q)), initial=0.0))
        if residual > CLOSURE_TOL:
            raise MalformedDescription(where, f"pose {i} does not close its loops (residual {residual:.2e})")
    return poses


def scene_times(mechanism: Mechanism, name: str, poses: int) -> np.ndarray:
    """Times (s) of a scene's poses: the spec's time axis for a time-parametrised scene, else one
    `SCENE_STEP` per pose from 0.

    Args:
        mechanism: the mechanism.
        name: one of its scenes.
        poses: the number of poses.

    Returns:
        The times (s), shape (poses,), increasing.

    Raises:
        MalformedDescription: the spec's time axis is not `poses` increasing finite times.
    """
    declared = mechanism.spec.scene_times.get(name)
    if declared is None:
        return SCENE_STEP * np.arange(poses, dtype=float)
    t = np.asarray(declared(mechanism, poses), dtype=float)
    if t.shape != (poses,) or not np.all(np.isfinite(t)) or np.any(np.diff(t) <= 0):
        raise MalformedDescription(
            f"{mechanism.spec.name} scene {name!r}", f"time axis is not {poses} strictly increasing finite times"
        )
    return t


def sweep(
    mechanism: Mechanism, frames: int = SWEEP_FRAMES, angle: float = SWEEP_ANGLE, stroke: float = SWEEP_STROKE
) -> list[np.ndarray]:
    """Generic scene: each actuated input in turn goes home -> +A -> home -> -A -> home (one sine period,
    sampled at `frames` poses) while the others stay at home.

    Each excursion is assembled outwards from home, each pose from the previous one, and comes back
    through the same poses. An excursion stops at its first pose that does not assemble (a dead point,
    a singularity, the edge of the workspace): a `SweepStopped` warning says which and why, and the
    scene goes on with the next excursion.

    Both amplitudes are capped at 90 % of the distance from home to the joint's limits.

    Args:
        mechanism: the mechanism.
        frames: poses per input (a multiple of 4).
        angle: amplitude A of a revolute input (rad).
        stroke: amplitude of a prismatic input, as a fraction of the mechanism's joint extent.

    Returns:
        The poses, home first and last, each (nq,).
    """
    model, home = mechanism.model, mechanism.home_q
    size = joint_extent(model, model.createData(), home)
    names = list(mechanism.actuated)
    start = np.array([home[mechanism.q_index(n)] for n in names])
    quarter = max(frames // 4, 1)
    poses = [home.copy()]
    for i, name in enumerate(names):
        k = mechanism.q_index(name)
        prismatic = model.joints[model.getJointId(name)].shortname().startswith("JointModelP")
        amplitude = stroke * size if prismatic else angle
        room = min(model.upperPositionLimit[k] - home[k], home[k] - model.lowerPositionLimit[k])
        amplitude = min(amplitude, 0.9 * room) if np.isfinite(room) else amplitude
        for sign in (1.0, -1.0):
            out, q = [], home
            for step in range(1, quarter + 1):
                inputs = start.copy()
                inputs[i] += sign * amplitude * math.sin(math.pi / 2 * step / quarter)
                try:
                    q = mechanism.assemble(inputs, guess=q)
                except (MechkitError, FloatingPointError) as err:
                    warnings.warn(
                        SweepStopped(
                            f"{mechanism.spec.name} sweep of {name} stops at {inputs[i]:.6g} (home {start[i]:.6g}): "
                            f"inputs {dict(zip(names, np.round(inputs, 6).tolist()))} do not assemble ({err})"
                        ),
                        stacklevel=2,
                    )
                    break
                out.append(q)
            if out:
                poses.extend([*out, *out[-2::-1], home.copy()])
    return poses
