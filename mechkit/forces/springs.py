"""Joint springs and dampers (`mechkit.core.JointSpring` records) as generalised forces.

A one-freedom joint (revolute, prismatic, helical; a continuous joint by its angle): effort = preload
- stiffness (x - reference) - damping dx/dt. A joint of several freedoms (ball, free-flyer): a damper
only, -damping v on each of its velocity coordinates (MuJoCo's joint damping). A revolute or prismatic
loop-cut joint (given the cuts): the same law on the cut's value, as body wrenches
(`mechkit.forces.cut_joints`).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import InvalidParameters
from mechkit.core import JointSpring
from mechkit.forces.cut_joints import CutJointSprings
from mechkit.forces.element import ForceElement, ForceState, Load, generalized_of_wrenches


class JointSprings(ForceElement):
    """The springs and dampers of one model, evaluated for one state or a leading sample axis.

    As a force element: the springs' potential is `energy`, the dampers' power (-damping v^2) the
    dissipated part.

    Args:
        model: the tree's Pinocchio model.
        springs: the records.
        name: the element's name.
        cuts: the cuts' rows (`ClosureModel.kernel.cuts`) where springs act on loop-cut joints.

    Raises:
        InvalidParameters: an unknown joint, a negative stiffness or damping, a spring (stiffness or
            preload) on a joint of several freedoms, or on a cut neither revolute nor prismatic.
    """

    def __init__(self, model: pin.Model, springs: Sequence[JointSpring], name: str = "springs", cuts: Sequence = ()):
        self.name = name
        self.springs = tuple(springs)
        self.role = "dissipative" if any(s.damping for s in self.springs) else "conservative"
        cut_names = {c.closure.name for c in cuts}
        on_cuts = [s for s in self.springs if s.joint in cut_names]
        self._model, self._cuts = model, (CutJointSprings(model, cuts, on_cuts, name) if on_cuts else None)
        q_index, v_index, unbounded, laws, damped_v, damped = [], [], [], [], [], []
        for s in self.springs:
            if s.joint in cut_names:
                continue
            if not model.existJointName(s.joint):
                where = f"; cut joints: {sorted(cut_names)}" if cuts else " (a loop-cut joint's: pass the cuts)"
                raise InvalidParameters("spring", s.joint, f"no such joint; joints: {list(model.names[1:])}{where}")
            j = model.getJointId(s.joint)
            jm = model.joints[j]
            if jm.nv == 1:
                q_index.append(jm.idx_q)
                v_index.append(jm.idx_v)
                unbounded.append(jm.nq == 2)
                laws.append((s.stiffness, s.reference, s.preload, s.damping))
            elif s.stiffness or s.preload:
                raise InvalidParameters(
                    f"spring on {s.joint}",
                    s,
                    f"a {jm.shortname()} joint has {jm.nv} freedoms: "
                    "only a damper acts on it (stiffness and preload 0)",
                )
            else:
                damped_v += range(jm.idx_v, jm.idx_v + jm.nv)
                damped += [s.damping] * jm.nv
        self._q, self._v = np.array(q_index, dtype=int), np.array(v_index, dtype=int)
        self._unbounded = np.array(unbounded, dtype=bool)
        self._k, self._ref, self._pre, self._d = (
            (np.array(c, dtype=float) for c in zip(*laws)) if laws else (np.zeros(0),) * 4
        )
        self._damped_v, self._damped = np.array(damped_v, dtype=int), np.array(damped, dtype=float)

    def __bool__(self) -> bool:
        return bool(self.springs)

    def _on_cuts(self, q: np.ndarray, v: np.ndarray | None, what: str) -> np.ndarray:
        """The cut joints' springs' generalised forces (..., nv) (what "forces") or potential (...,) ("energy"),
        sample by sample (each needs the kinematics of its q)."""
        model, data = self._model, self._model.createData()
        lead = np.shape(q)[:-1]
        qs = np.reshape(q, (-1, model.nq))
        vs = np.zeros((len(qs), model.nv)) if v is None else np.reshape(v, (-1, model.nv))
        out = []
        for qi, vi in zip(qs, vs):
            state = ForceState.at(model, data, qi, vi)
            if what == "energy":
                out.append(self._cuts.energy(model, data, qi))
            else:
                out.append(generalized_of_wrenches(model, data, self._cuts.load(state).wrenches))
        return np.reshape(np.array(out), lead + ((model.nv,) if what == "forces" else ()))

    def values(self, q: np.ndarray) -> np.ndarray:
        """The one-freedom tree joints' springs' joint values.

        Args:
            q: (..., nq) configurations.

        Returns:
            (..., k) the joint values x (rad or m; a continuous joint's angle), k the one-freedom springs.
        """
        x = q[..., self._q]
        if self._unbounded.any():
            x = np.where(
                self._unbounded, np.arctan2(q[..., np.minimum(self._q + 1, q.shape[-1] - 1)], q[..., self._q]), x
            )
        return x

    def forces(self, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        """The springs' and dampers' generalised forces.

        Args:
            q: (..., nq) configurations.
            v: (..., nv) velocities.

        Returns:
            (..., nv) generalised forces (N m or N).
        """
        out = self._tree_forces(q, v)
        return out if self._cuts is None else out + self._on_cuts(q, v, "forces")

    def _tree_forces(self, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        """The tree joints' springs' and dampers' generalised forces (..., nv)."""
        out = np.zeros(np.shape(v))
        out[..., self._v] = self._pre - self._k * (self.values(q) - self._ref) - self._d * v[..., self._v]
        out[..., self._damped_v] -= self._damped * v[..., self._damped_v]
        return out

    def potential(self, q: np.ndarray) -> np.ndarray:
        """The springs' potential energy: sum of stiffness (x - reference)^2 / 2 - preload (x - reference).

        Args:
            q: (..., nq) configurations.

        Returns:
            (...,) the potential energy (J).
        """
        dx = self.values(q) - self._ref
        out = np.sum(0.5 * self._k * dx**2 - self._pre * dx, axis=-1)
        return out if self._cuts is None else out + self._on_cuts(q, None, "energy")

    def damper_power(self, v: np.ndarray) -> np.ndarray:
        """The tree joints' dampers' power: -sum of damping v^2 (a cut's damper: `load`).

        Args:
            v: (..., nv) velocities.

        Returns:
            (...,) the power (W, <= 0).
        """
        return -(
            np.sum(self._d * v[..., self._v] ** 2, axis=-1)
            + np.sum(self._damped * v[..., self._damped_v] ** 2, axis=-1)
        )

    def load(self, state: ForceState) -> Load:
        """Springs and dampers at a state.

        Args:
            state: the state (its q and v are read).

        Returns:
            The `Load`: generalised forces (nv,) at the tree joints, body wrenches (njoints, 6) of the cut
            joints' springs (or None), the dampers' power (W, <= 0).
        """
        out = self._tree_forces(state.q, state.v)
        power = float(self.damper_power(state.v))
        if self._cuts is None:
            return Load(out, None, power)
        cut = self._cuts.load(state)
        return Load(out, cut.wrenches, power + cut.power)

    def energy(self, model: pin.Model, data: pin.Data, q: np.ndarray) -> float:
        """The springs' potential energy at q.

        Args:
            model: the tree's Pinocchio model.
            data: its data after `forwardKinematics(q)` (read for the cut joints' springs).
            q: (nq,) configuration.

        Returns:
            The potential energy (J).
        """
        dx = self.values(q) - self._ref
        tree = float(np.sum(0.5 * self._k * dx**2 - self._pre * dx))
        return tree if self._cuts is None else tree + self._cuts.energy(model, data, q)
