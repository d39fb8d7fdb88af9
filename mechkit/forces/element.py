"""What every force element shares: the state it is evaluated at, the load it gives, its energy roles.

A force element (`ForceElement`) is a named object that, at a state (`ForceState`: q, v, t, the
Pinocchio kinematics of q and v and, for friction, every joint's reaction), gives a `Load`: generalised
forces at the tree joints (nv,) and body wrenches (njoints, 6) in Pinocchio's `fext` convention (the
wrench [f, m] on joint i's body, in joint i's frame, about its origin). Each element also says how its
power enters the energy balance: a conservative part by its potential `energy(q)` (J), the rest by
`Load.power` (W; negative for dissipation), so that kinetic + potential - the work of sources + the
energy dissipated stays constant along any motion.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

#: Roles of an element's non-conservative power in the energy balance.
ROLES = ("conservative", "dissipative", "source")


@dataclass
class ForceState:
    """One state at which force elements are evaluated.

    Attributes:
        model: the tree's Pinocchio model.
        data: its Pinocchio data after `forwardKinematics(q, v)`, `computeJointJacobians(q)` and
            `updateFramePlacements` (world placements, velocities, J).
        q: (nq,) configuration.
        v: (nv,) velocities.
        t: time (s).
        reactions: (n_joints, 6) every joint's reaction [f (N), m (N m)], world axes, about the joint
            origin, parent side on child side, in `ClosureModel.joint_names` order (tree joints, then
            cut joints); None where no reaction is known yet.
    """

    model: pin.Model
    data: pin.Data
    q: np.ndarray
    v: np.ndarray
    t: float
    reactions: np.ndarray | None = None

    @classmethod
    def at(cls, model: pin.Model, data: pin.Data, q: np.ndarray, v: np.ndarray, t: float = 0.0) -> ForceState:
        """The state with its kinematics computed in `data`.

        Args:
            model: the tree's Pinocchio model.
            data: a data of `model`, overwritten with the kinematics of (q, v).
            q: (nq,) configuration.
            v: (nv,) velocities.
            t: time (s).

        Returns:
            The `ForceState` (no reactions).
        """
        pin.forwardKinematics(model, data, q, v)
        pin.computeJointJacobians(model, data, q)
        pin.updateFramePlacements(model, data)
        return cls(model, data, q, v, t)


@dataclass
class Load:
    """What one element applies at one state.

    Attributes:
        generalized: (nv,) generalised forces at the tree joints (N m or N), or None.
        wrenches: (njoints, 6) body wrenches, Pinocchio's `fext` convention (joint frames), or None.
        power: power of the non-conservative part (W): negative where the element dissipates.
    """

    generalized: np.ndarray | None = None
    wrenches: np.ndarray | None = None
    power: float = 0.0


class ForceElement:
    """Base of the named force elements (`mechkit.forces`).

    Attributes:
        name: the element's name (columns `work/<name>` of a simulation).
        role: how its non-conservative power counts: "dissipative" (dampers, friction), "source"
            (motors, external wrenches) or "conservative" (springs without dampers, gravity).
        needs_reactions: its load depends on the joint reactions (friction from the reaction).
        friction: it is joint friction (its power is a simulation's friction power).
    """

    name: str = "force"
    role: str = "conservative"
    needs_reactions: bool = False
    friction: bool = False

    def load(self, state: ForceState) -> Load:
        """The element's load at a state.

        Args:
            state: the state, its kinematics computed (`ForceState.at`).

        Returns:
            The `Load`: generalised forces, body wrenches and non-conservative power.

        Raises:
            NotImplementedError: always here; each element defines its own.
        """
        raise NotImplementedError

    def energy(self, model: pin.Model, data: pin.Data, q: np.ndarray) -> float:
        """Potential energy of the conservative part at q.

        Args:
            model: the tree's Pinocchio model.
            data: its data after `forwardKinematics(q)`.
            q: (nq,) configuration.

        Returns:
            The potential energy (J); 0 here (an element without a conservative part).
        """
        return 0.0


def generalized_of_wrenches(model: pin.Model, data: pin.Data, wrenches: np.ndarray) -> np.ndarray:
    """Generalised forces J^T f of body wrenches.

    Args:
        model: the tree's Pinocchio model.
        data: its data after `computeJointJacobians(q)` (world Jacobians and placements).
        wrenches: (njoints, 6) body wrenches in Pinocchio's `fext` convention (joint frames, about the
            joint origins; row 0, the ground, ignored).

    Returns:
        (nv,) the generalised forces (N m or N).
    """
    out = np.zeros(model.nv)
    for j in np.flatnonzero(np.any(wrenches != 0.0, axis=1)):
        if j == 0:
            continue
        f_world = data.oMi[int(j)].act(pin.Force(wrenches[j]))  # about the world origin, world axes
        out += pin.getJointJacobian(model, data, int(j), pin.WORLD).reshape(6, -1).T @ f_world.vector
    return out


def wrench_on_body(
    model: pin.Model, data: pin.Data, joint: int, force: np.ndarray, moment: np.ndarray, point: np.ndarray
) -> np.ndarray:
    """A world force through a world point plus a world moment on one body, as its `fext` row.

    Args:
        model: the tree's Pinocchio model.
        data: its data after `forwardKinematics(q)` (world placements `oMi`).
        joint: the Pinocchio id of the joint whose body is loaded.
        force: (3,) the force (N, world axes).
        moment: (3,) the moment (N m, world axes).
        point: (3,) the force's point (m, world).

    Returns:
        (6,) the wrench [f, m] in the joint's frame, about the joint origin.
    """
    M = data.oMi[joint]
    arm = point - M.translation
    world = np.concatenate([force, moment + np.cross(arm, force)])  # about the joint origin, world axes
    R = M.rotation
    return np.concatenate([R.T @ world[:3], R.T @ world[3:]])
