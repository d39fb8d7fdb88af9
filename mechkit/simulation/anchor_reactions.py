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

from mechkit.core import tree_wrenches


class AnchorReactions:
    """The reactions of a closure model's joints from the multipliers of its legacy anchors.

    Args:
        cm (ClosureModel): the closure model (its cuts in `kernel.cuts` order; no coupling rows).
        legacy (LegacyConstraints): its anchors (`core.forward` keeps them in `ClosureData.legacy["proximal"]`).
    """

    def __init__(self, cm, legacy):
        self.model, self.legacy = cm.model, legacy
        self.scratch = (
            cm.create_data()
        )  # its Pinocchio data for the RNEA pass, with views of its placements and wrenches
        self.n_tree = self.model.njoints - 1
        self.spans = []  # per cut: its anchors' (model, first multiplier, size); the first at the cut's point
        start, anchors = 0, list(zip(legacy.models, legacy.sizes))
        for cut in cm.kernel.cuts:
            count = 2 if cut.closure.kind == "revolute" and cut.closure.rows != "planar" else 1
            span = []
            for c, size in anchors[:count]:
                span.append((c, start, size))
                start += size
            anchors = anchors[count:]
            self.spans.append(span)
        self.size = start
        self._fext = pin.StdVec_Force()
        for _ in range(self.model.njoints):
            self._fext.append(pin.Force.Zero())

    def __call__(
        self, placed: pin.Data, q: np.ndarray, v: np.ndarray, a: np.ndarray, lam: np.ndarray, wrenches: np.ndarray
    ) -> np.ndarray:
        """The reactions at a state.

        Args:
            placed: a data of the tree with the joint placements at q (`pin.forwardKinematics`).
            q: (nq,) configuration.
            v: (nv,) velocities.
            a: (nv,) the accelerations the multipliers came with.
            lam: (rows,) the anchors' multipliers (`pin.Data.lambda_c` after `constraintDynamics`).
            wrenches: (njoints, 6) the force elements' body wrenches (`fext` convention).

        Returns:
            (n_tree + n_cuts, 6) [f (N), m (N m) about the joint's point], world axes, in
            `ClosureModel.joint_names` order.
        """
        model = self.model
        fext = wrenches.copy()
        cuts = np.zeros((len(self.spans), 6))
        for i, span in enumerate(self.spans):
            at_point = None
            for c, start, size in span:
                f = lam[start : start + size]
                force = pin.Force(f, np.zeros(3)) if size == 3 else pin.Force(f)
                oMc = placed.oMi[c.joint1_id] * c.joint1_placement
                if at_point is None:  # the first anchor: at the cut's point
                    at_point = pin.SE3(np.eye(3), oMc.translation)
                fext[c.joint1_id] += c.joint1_placement.act(force).vector
                if c.joint2_id:
                    fext[c.joint2_id] -= placed.oMi[c.joint2_id].actInv(oMc).act(force).vector
                cuts[i] += at_point.actInv(oMc.act(force)).vector  # world axes, about the cut's point
        for j in range(1, model.njoints):
            self._fext[j] = pin.Force(fext[j])
        pin.forwardKinematics(model, self.scratch.pin, q)  # the placements the views read (rnea leaves oMi)
        pin.rnea(model, self.scratch.pin, q, v, a, self._fext)
        return np.concatenate((tree_wrenches(self.scratch.oMi, self.scratch.f), -cuts))
