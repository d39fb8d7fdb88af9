"""What a mechanism's description declares for a simulation: its force elements (springs, the dampers and
friction of a URDF's `<dynamics>` or an MJCF's `frictionloss`), its joint limits, and the envelopes of
the torque motors that given efforts drive."""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from mechkit.base.exceptions import InvalidParameters
from mechkit.forces import SPEED_THRESHOLD, ForceElement, TorqueMotor, read_described
from mechkit.simulation.events import Limit


def default_forces(
    mech: Any, source: str | Path | None = None, threshold: float = SPEED_THRESHOLD
) -> list[ForceElement]:
    """The force elements a mechanism's description declares.

    Args:
        mech: the mechanism (`mechkit.Mechanism`).
        source: the MJCF file it came from (whose URDF the mechanism does not keep), or None: its URDF
            is read.
        threshold: the regularisation rate of its constant friction (rad/s or m/s, > 0).

    Returns:
        Its joint springs (`Mechanism.springs`), then the dampers and friction of its URDF `<dynamics>`
        or its MJCF `frictionloss`, then its point-to-point elements (`<mechkit:strut>`, MJCF spatial
        tendons).

    Raises:
        InvalidParameters: a threshold not > 0.
    """
    out: list[ForceElement] = [mech.springs] if mech.springs else []
    return out + read_described(source, mech.urdf, mech.model, tuple(mech.actuated)).elements(mech.model, threshold)


def file_limits(mech: Any, source: str | Path | None = None, restitution: float = 0.0) -> list[Limit]:
    """The joint limits the description declares (URDF `<limit>`, MJCF `range` of limited joints).

    Args:
        mech: the mechanism (`mechkit.Mechanism`).
        source: the MJCF file it came from, or None: its URDF is read.
        restitution: the limits' restitution (0: stop and hold; 1: elastic).

    Returns:
        One `Limit` per limited joint.
    """
    described = read_described(source, mech.urdf, mech.model, tuple(mech.actuated))
    return [Limit(j, lo, hi, restitution) for j, (lo, hi) in described.limits.items()]


def torque_motors(mech: Any, torques: Any, source: str | Path | None = None) -> list[TorqueMotor]:
    """Torque motors on the actuators from given efforts, each within the envelope its description gives
    (`mechkit.forces.motors`).

    Args:
        mech: the mechanism (`mechkit.Mechanism`).
        torques: a mapping actuator -> effort (N m or N; a constant or a function of t), a sampled law
            (`names`, `t`, `values`: linear between samples, held after the last), or None.
        source: the MJCF file it came from (its force ranges), or None: its URDF is read.

    Returns:
        One `TorqueMotor` per actuator given (none for None).

    Raises:
        InvalidParameters: a name that is not an actuator, or a mechanism without actuators.
    """
    if torques is None:
        return []
    if not isinstance(torques, Mapping):
        t, values = np.asarray(torques.t, dtype=float), np.asarray(torques.values, dtype=float)
        torques = {n: (lambda s, k=k: float(np.interp(s, t, values[:, k]))) for k, n in enumerate(torques.names)}
    mech.require_actuators("given torques")
    envelopes = read_described(source, mech.urdf, mech.model, tuple(mech.actuated)).motors
    S = mech.closure_model.actuation
    out = []
    for name, command in torques.items():
        if name not in mech.actuated:
            raise InvalidParameters("torques", name, f"not an actuator; actuators: {list(mech.actuated)}")
        stall, no_load = envelopes.get(name, (math.inf, math.inf))
        out.append(TorqueMotor(S[mech.actuated.index(name)], command, stall, no_load, name))
    return out
