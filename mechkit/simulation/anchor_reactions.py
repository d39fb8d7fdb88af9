"""Every joint's reaction from the multipliers of Pinocchio's constrained forward dynamics ("proximal"):
no inverse dynamics.

`pin.constraintDynamics` solves M a + nle = tau + J^T lambda on its point (3D) and weld (6D) anchors
(`mechkit.core.pin_constraints`): lambda is each anchor's force in its first frame (LOCAL), acting on
the first side's body and, opposite, on the second's. A cut joint transmits its anchors' forces (about
the cut's point, frame_a's origin); a tree joint transmits what one RNEA pass gives with the anchors'
forces applied to their bodies beside the force elements' wrenches. These are the reactions of the
state's own accelerations and forces: at an integrator's stage off the closures they are those of
Pinocchio's rows, where the core's inverse dynamics on mechkit's rows refuses a force outside their
range. For the components statics leaves undetermined (a planar loop in space: the axial force, the
bending moment) they are a convention, as the inverse dynamics' least-norm ones are: friction from
the reactions uses the determined ones (`mechkit.forces.reaction_friction`).
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit.core import ClosureModel, tree_wrenches


def applies(cm: ClosureModel) -> bool:
    """Whether the anchors' multipliers give the reactions the core's inverse dynamics gives: every cut a
    planar revolute or a spherical one (one point anchor, the same rows as mechkit's). Two anchors on a
    revolute axis (spatial or spherical-rows cuts) and 6D welds regularise a different self-stress: where
    statics leaves a force undetermined (the spherical 2-dof's, by up to its size) friction from it would
    differ from the inverse dynamics' least-norm one, so the simulation keeps "kkt" and the inverse dynamics.

    Args:
        cm: the closure model.

    Returns:
        True where the reactions from the anchors are the inverse dynamics' ones.
    """
    cuts = cm.kernel.cuts
    return not cm.kernel.couplings and all(
        c.closure.kind == "spherical" or (c.closure.kind == "revolute" and c.closure.rows == "planar") for c in cuts
    )


class AnchorReactions:
    """The reactions of a closure model's joints from the multipliers of its legacy anchors.

    Args:
        cm (ClosureModel): the closure model (its cuts in `kernel.cuts` order; no coupling rows).
        legacy (LegacyConstraints): its anchors (`core.forward` keeps them in `ClosureData.legacy["proximal"]`).
    """

    def __init__(self, cm, legacy):
        self.model, self.legacy = cm.model, legacy
        self.scratch = cm.create_data()  # the RNEA pass's data, with views of its placements and wrenches
        nj = self.model.njoints
        self.spans = []  # per cut: its anchors' (model, first multiplier, size); the first at the cut's point
        start, anchors = 0, list(zip(legacy.models, legacy.sizes))
        for cut in cm.kernel.cuts:
            count = 2 if cut.closure.kind == "revolute" and cut.closure.rows != "planar" else 1
            span = []
            for c, size in anchors[:count]:
                span.append((c, start, size))
                start += size
            self.spans.append(span)
            anchors = anchors[count:]
        self.size = start
        self._fext = pin.StdVec_Force()
        for _ in range(nj):
            self._fext.append(pin.Force.Zero())
        self._fext_rows = _stacked_forces(self._fext)
        self._still = np.zeros(self.model.nv)  # v = a = 0 for `generalized`
        #: (nj * 6 + n_cuts * 6, rows): multipliers -> the anchors' body wrenches (`fext`) and the cuts'
        #: reactions (world axes, about each cut's point), at the state `at` was given.
        self._map = np.zeros((6 * (nj + len(self.spans)), start))
        self._fixed = np.zeros_like(self._map)  # the first side's part: its anchor is fixed on that body
        for span in self.spans:
            for c, first, size in span:
                j1 = c.joint1_id
                self._fixed[6 * j1 : 6 * j1 + 6, first : first + size] += c.joint1_placement.dualAction[:, :size]

    def at(self, placed: pin.Data) -> None:
        """Set the state: the map from multipliers to body wrenches and cut reactions (linear at a q).

        Args:
            placed: a data of the tree with the joint placements at the state's q (`pin.forwardKinematics`).
        """
        nj, out = self.model.njoints, self._map
        out[:] = self._fixed
        for i, span in enumerate(self.spans):
            point = None
            for c, start, size in span:
                columns = slice(start, start + size)
                oMc = placed.oMi[c.joint1_id] * c.joint1_placement
                if point is None:  # the first anchor: at the cut's point
                    point = oMc.translation
                if c.joint2_id:
                    j2 = c.joint2_id
                    out[6 * j2 : 6 * j2 + 6, columns] -= placed.oMi[j2].actInv(oMc).dualAction[:, :size]
                row = 6 * (nj + i)  # the cut transmits minus the force its anchors put on frame_a's side
                out[row : row + 6, columns] -= pin.SE3(oMc.rotation, oMc.translation - point).dualAction[:, :size]

    def __call__(
        self, q: np.ndarray, v: np.ndarray, a: np.ndarray, lam: np.ndarray, wrenches: np.ndarray
    ) -> np.ndarray:
        """The reactions at the state `at` was given.

        Args:
            q: (nq,) configuration.
            v: (nv,) velocities.
            a: (nv,) the accelerations the multipliers came with.
            lam: (rows,) the anchors' multipliers (`pin.Data.lambda_c` after `constraintDynamics`).
            wrenches: (njoints, 6) the force elements' body wrenches (`fext` convention).

        Returns:
            (n_tree + n_cuts, 6) [f (N), m (N m) about the joint's point], world axes, in
            `ClosureModel.joint_names` order.
        """
        nj, model = self.model.njoints, self.model
        loads = (self._map @ lam).reshape(-1, 6)
        self._fext_rows[:] = wrenches + loads[:nj]
        pin.forwardKinematics(model, self.scratch.pin, q)  # the placements the views read (rnea leaves oMi)
        pin.rnea(model, self.scratch.pin, q, v, a, self._fext)
        return np.concatenate((tree_wrenches(self.scratch.oMi, self.scratch.f), loads[nj:]))

    def generalized(self, q: np.ndarray, wrenches: np.ndarray) -> np.ndarray:
        """Generalised forces J^T f of body wrenches, by two Pinocchio passes: g(q) - rnea(q, 0, 0, f)
        (`forces.generalized_of_wrenches`'s quantity, without a Jacobian per body).

        Args:
            q: (nq,) configuration.
            wrenches: (njoints, 6) body wrenches (`fext` convention; row 0 ignored).

        Returns:
            (nv,) the generalised forces (N m or N).
        """
        self._fext_rows[:] = wrenches
        self._fext_rows[0] = 0.0
        data = self.scratch.pin
        gravity = pin.computeGeneralizedGravity(self.model, data, q).copy()
        return gravity - pin.rnea(self.model, data, q, self._still, self._still, self._fext)


def _stacked_forces(forces: pin.StdVec_Force) -> np.ndarray:
    """(n, 6) a writable view of a vector of Pinocchio forces (one contiguous buffer in Pinocchio 4.1).

    Raises:
        RuntimeError: the forces are not one buffer of 6 doubles each.
    """
    views = [f.np for f in forces.tolist()]
    first = views[0].__array_interface__["data"][0]
    if any(view.__array_interface__["data"][0] != first + 48 * k for k, view in enumerate(views)):
        raise RuntimeError("pin.StdVec_Force is not one buffer of 6 doubles per force")
    return np.lib.stride_tricks.as_strided(views[0], shape=(len(views), 6), strides=(48, 8), writeable=True)
