"""Kinematics along a path: per sample, the closure solve from a warm start, then velocities and
accelerations from one closure Jacobian, and the joint axes in world axes.

The same steps as `Mechanism.assemble`, `velocities` and `accelerations` (the core's
`kinematics.solve_closure` and `project_velocity`), with what they recompute per call done once:
the input and free velocity indices are fixed for the whole path, and the closure Jacobian that the
solve leaves current at q serves both projections.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pinocchio as pin

from mechkit import kinematics
from mechkit.mechanism import Mechanism


class JointAxes:
    """Unit axes (world frame) of every joint: tree joints in model order, then the cuts of `mech.rows`.

    Tree joints of one degree of freedom: the rotation axis (revolute) or the sliding direction
    (prismatic), from the joint's motion subspace. Cut joints: the declared axis of a revolute or
    prismatic closure, in frame_a's frame. Other joints (spherical, Hooke, weld) have no single axis: NaN.
    """

    def __init__(self, mech: Mechanism):
        model = mech.model
        data = model.createData()
        pin.forwardKinematics(model, data, mech.home_q)
        self.tree = np.full((model.njoints, 3), np.nan)
        for j in range(1, model.njoints):
            if model.joints[j].nv == 1:
                S = np.asarray(data.joints[j].S).reshape(6)
                local = S[3:] if np.linalg.norm(S[3:]) > 0 else S[:3]
                self.tree[j] = local / np.linalg.norm(local)
        self.cuts = [(c.frame_a, np.asarray(c.closure.axis, dtype=float) if c.closure.kind in ("revolute", "prismatic")
                      else np.full(3, np.nan)) for c in mech.rows.cuts]

    def world(self, data: pin.Data) -> np.ndarray:
        """(n_joints, 3) world axes at the configuration `data` holds (joint and frame placements current)."""
        R = np.array([data.oMi[j].rotation for j in range(1, len(self.tree))]).reshape(-1, 3, 3)
        tree = np.einsum("jab,jb->ja", R, self.tree[1:])
        cuts = [data.oMf[f].rotation @ axis for f, axis in self.cuts]
        return np.vstack([tree, *cuts]) if cuts else tree


class PathKinematics:
    """The kinematics of one mechanism along a path of given input coordinates.

    Args:
        mech: the mechanism.
        names: the given (driven) joints, one coordinate each.
    """

    def __init__(self, mech: Mechanism, names: Sequence[str]):
        self.mech, self.model = mech, mech.model
        self.data = mech.model.createData()
        self.input_q = np.array([mech.q_index(j) for j in names], dtype=int)
        self.input_v = np.array([mech.v_index(j) for j in names], dtype=int)
        self.free_v = np.setdiff1d(np.arange(mech.model.nv), self.input_v)
        self.names = tuple(names)
        self.axes = JointAxes(mech)

    def first_guess(self, values: np.ndarray) -> np.ndarray:
        """The assembly at the first sample from the mechanism's own guess (its branch)."""
        return self.mech.assemble(dict(zip(self.names, values)))

    def sample(self, guess: np.ndarray, values: np.ndarray, rates: np.ndarray, accelerations: np.ndarray,
               tol: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """q, v, a and the joint axes (world) at one sample, the loops closed from `guess`.

        Raises:
            ClosureNotConverged: no assembly near the guess.
            SingularConfiguration: the inputs do not determine the motion there.
        """
        model, data, rows = self.model, self.data, self.mech.rows
        q0 = np.array(guess, dtype=float)
        q0[self.input_q] = values
        q, _ = kinematics.solve_closure(rows, data, q0, self.free_v, tol=tol)
        J = rows.jacobian(data)  # the solve leaves joint Jacobians and frames current at q
        axes = self.axes.world(data)
        independent = self.mech.independent_rows
        v = kinematics.project_velocity(J, rates, self.input_v, self.free_v, independent)
        pin.forwardKinematics(model, data, q, v, np.zeros(model.nv))
        pin.updateFramePlacements(model, data)
        gamma = rows.drift(data)
        a = kinematics.project_velocity(J, accelerations, self.input_v, self.free_v, independent, rhs=gamma)
        return q, v, a, axes
