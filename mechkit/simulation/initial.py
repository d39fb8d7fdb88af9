"""Initial velocities of a simulation: some joints' rates completed to a velocity of the closed loops, or
an MJCF keyframe's qvel.

`rates_velocity`: the given joints take their rates and the other coordinates the smallest rates the
closures allow, v_F = -J_F^+ J_G v_G (the projection's velocity step, `Projection.velocities`):
for the N four-bar, crank0's rate alone gives the whole parallelogram's. Rates the closures do not allow
together (two cranks of a parallelogram at different rates) are refused naming them.

`keyframe_velocity`: the qvel of an MJCF keyframe (by default "home", the one the pose comes from) in
Pinocchio's coordinates: a hinge's or slide's rate as it is, a ball's angular velocity (MuJoCo's and
Pinocchio's are both in the body frame), a free joint's origin velocity turned from the world frame into
the body frame (Pinocchio's free flyer) and its body-frame angular velocity; then put onto the closures
by the same completion with no joint given (a keyframe's velocity need not satisfy them exactly).
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
import pinocchio as pin

from mechkit import core
from mechkit.base.exceptions import InvalidArgument, MalformedDescription
from mechkit.simulation.prescribed import Drives
from mechkit.simulation.projection import Projection

#: Largest |J v| of a completed velocity, relative to |J| |v| (ours: far above rounding, far below a
#: contradiction between the given rates).
CONSISTENCY_TOL = 1e-9


def rates_velocity(mech: Any, rates: Mapping[str, float], q: np.ndarray, option: str = "v0") -> np.ndarray:
    """A velocity of the closed loops with some joints at given rates.

    Args:
        mech (Mechanism): the mechanism.
        rates: joint -> rate (rad/s or m/s), one-freedom joints.
        q: (nq,) an assembled configuration.
        option: the argument's name for errors (e.g. "--v0").

    Returns:
        (nv,) the velocity: the given rates, the other coordinates the smallest the closures allow.

    Raises:
        InvalidArgument: a joint that is not a one-freedom joint of the mechanism, a rate that is not finite,
            or rates the closures do not allow together.
    """
    model = mech.model
    names = list(model.names[1:])
    v = np.zeros(model.nv)
    given = []
    for joint, rate in rates.items():
        if joint not in names:
            raise InvalidArgument(option, joint, f"no such joint; the joints: {', '.join(names)}")
        if model.joints[model.getJointId(joint)].nv != 1:
            raise InvalidArgument(option, joint, "takes one-freedom joints (revolute, prismatic) only")
        if not np.isfinite(rate):
            raise InvalidArgument(option, f"{joint}={rate}", "a rate must be a finite number (rad/s or m/s)")
        k = mech.v_index(joint)
        v[k] = float(rate)
        given.append(k)
    if not given:
        return Projection(mech).velocities(q, v, Drives(), 0.0)
    joints, values, given_rates = tuple(rates), q[[mech.q_index(j) for j in rates]], v[given].copy()
    law = Drives(joints, lambda t: (values, given_rates, np.zeros(len(joints))))
    v = Projection(mech).velocities(q, v, law, 0.0)
    J = core.closure_jacobian(mech.closure_model, mech.closure_model.create_data(), q)
    left = float(np.max(np.abs(J @ v), initial=0.0))
    scale = float(np.max(np.abs(J), initial=0.0)) * float(np.max(np.abs(v), initial=0.0))
    if left > CONSISTENCY_TOL * max(scale, 1e-300):
        listed = ", ".join(f"{j}={r:g}" for j, r in rates.items())
        raise InvalidArgument(
            option, listed, f"the closures do not allow these rates together (|J v| = {left:.3g}): give fewer joints"
        )
    return v


def keyframe_velocity(mech: Any, path: str | Path, q: np.ndarray, key: str = "home") -> np.ndarray | None:
    """The qvel of an MJCF file's keyframe as a velocity of the closed loops.

    Args:
        mech (Mechanism): the mechanism read from that file.
        path: the MJCF file.
        q: (nq,) the assembled configuration the velocity is taken at.
        key: the keyframe's name.

    Returns:
        (nv,) the velocity, or None where the file has no such keyframe.

    Raises:
        MalformedDescription: a keyframe joint the mechanism does not have.
    """
    import mujoco

    from mechkit.sources.mjcf.tree import object_names

    mm = mujoco.MjModel.from_xml_path(str(path))
    k = mujoco.mj_name2id(mm, mujoco.mjtObj.mjOBJ_KEY, key)
    if k < 0:
        return None
    qvel = np.asarray(mm.key_qvel[k], dtype=float)
    model = mech.model
    v = np.zeros(model.nv)
    for j, name in enumerate(object_names(mujoco, mm)["joint"]):
        if name not in model.names:
            raise MalformedDescription(
                f"{path}: keyframe {key!r}", f"joint {name!r} is not a joint of {mech.spec.name}"
            )
        pj = model.getJointId(name)
        at, width = model.joints[pj].idx_v, model.joints[pj].nv
        rate = qvel[mm.jnt_dofadr[j] : mm.jnt_dofadr[j] + width].copy()
        if int(mm.jnt_type[j]) == int(mujoco.mjtJoint.mjJNT_FREE):
            x, y, z, w = q[model.joints[pj].idx_q + 3 : model.joints[pj].idx_q + 7]
            rate[:3] = pin.Quaternion(w, x, y, z).normalized().matrix().T @ rate[:3]
        v[at : at + width] = rate
    return Projection(mech).velocities(q, v, Drives(), 0.0)
