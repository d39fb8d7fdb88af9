"""Pinocchio's constraint API behind one module: the only place in mechkit that names it.

Pinocchio 4.1 keeps `RigidConstraintModel` (with `constraintDynamics`, `lcaba`) as its legacy
constraint API beside newer anchor models; its maintainers have said the legacy one will be
replaced (pinocchio issue 2816). Moving to the newer API touches this module alone.

The legacy models equivalent to mechkit's cuts: a weld -> one 6D anchor; a spherical or planar
revolute cut -> one 3D point anchor; a spatial (or spherical-rows) revolute cut -> two 3D point
anchors on its axis, `AXIS_ANCHOR_OFFSET` apart. Redundant rows are left to the proximal
regularisation. Hooke and prismatic cuts, and coupling rows, have no equivalent. Sign convention:
M a + nle = tau + J^T lambda.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import MethodUnavailable
from mechkit.core.cuts import CutRows

#: Offset (m) along a revolute axis of the second point anchor of a spatial revolute cut.
AXIS_ANCHOR_OFFSET = 0.1

#: Pinocchio's own proximal constrained dynamics, bare (for benchmarks that time it raw).
raw_constraint_dynamics: Callable = pin.constraintDynamics


class LegacyConstraints:
    """Pinocchio's legacy constraint models of a set of cuts, their datas, and a data initialised for them.

    Args:
        model: the tree's Pinocchio model.
        cuts: the cuts (their `closure.kind` and `rows` choose the anchors).
        couplings: number of coupling rows (must be 0: no legacy model expresses them).
        ordered: set the data up for `loop_constrained_aba` (Pinocchio's joint elimination order, which
            `constraintDynamics` must not see: a data serves one of the two).

    Raises:
        MethodUnavailable: a Hooke or prismatic cut, or a coupling row.
    """

    def __init__(self, model: pin.Model, cuts: list[CutRows], couplings: int = 0, ordered: bool = False):
        if couplings:
            raise MethodUnavailable(
                "pin.constraintDynamics",
                "coupling rows have no RigidConstraintModel; the kkt and nullspace methods solve them",
            )
        self.model = model
        self.models = pin.StdVec_RigidConstraintModel()
        for cm in _legacy_models(model, cuts):
            self.models.append(_ground_side_second(model, cm) if ordered else cm)
        self.datas = pin.StdVec_RigidConstraintData()
        for cm in self.models:
            self.datas.append(cm.createData())
        self.data = model.createData()
        pin.initConstraintDynamics(model, self.data, self.models, self.datas)
        self._rhs, self._lambda = self.data.primal_rhs_contact, self.data.lambda_c  # views of the data's buffers
        self.sizes = [3 if cm.type == pin.ContactType.CONTACT_3D else 6 for cm in self.models]
        self._gains = (0.0, 0.0)
        self.stabilised = False  # Baumgarte gains set (`set_baumgarte`)
        self.ordered = ordered
        if ordered:
            pin.computeJointMinimalOrdering(model, self.data, self.models)

    def set_baumgarte(self, gains: tuple[float, float] | None) -> None:
        """Set the Baumgarte gains on every model, when they change.

        Args:
            gains: (Kp (1/s^2), Kd (1/s)), or None: none.
        """
        gains = (0.0, 0.0) if gains is None else (float(gains[0]), float(gains[1]))
        if gains != self._gains:
            for cm in self.models:
                cm.setBaumgarteCorrectorParameters(pin.BaumgarteCorrectorParameters(*gains))
            self._gains = gains
            self.stabilised = gains != (0.0, 0.0)

    def dynamics(
        self, q: np.ndarray, v: np.ndarray, tau: np.ndarray, settings: pin.ProximalSettings
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Accelerations by `pin.constraintDynamics` (not for a data set up with `ordered`), with what a check
        of them and the constraint force need, in one call.

        Args:
            q: (nq,) configuration.
            v: (nv,) velocity.
            tau: (nv,) joint efforts (N m or N).
            settings: Pinocchio's proximal settings (`proximal_settings`); its outcome is written back.

        Returns:
            (nv,) the accelerations and (rows,) the multipliers lambda (M a + nle = tau + J^T lambda),
            copies; (rows, nv) the anchors' Jacobian at the state (`jacobian`) and (rows,) -gamma (-
            Baumgarte terms) of every row, `drift` negated as Pinocchio holds it (a view of its buffer).
        """
        assert not self.ordered, "a data set up for lcaba"
        # the accelerations come by value, an array of their own (not data.ddq: a test guards it)
        a = pin.constraintDynamics(self.model, self.data, q, v, tau, self.models, self.datas, settings)
        J = pin.getConstraintsJacobian(self.model, self.data, self.models, self.datas)
        return a, self._lambda.copy(), J if J.ndim == 2 else J.reshape(-1, self.model.nv), self._rhs

    def loop_constrained_aba(
        self, q: np.ndarray, v: np.ndarray, tau: np.ndarray, settings: pin.ProximalSettings
    ) -> np.ndarray:
        """Accelerations by `pin.lcaba` (needs `ordered`).

        Args:
            q: (nq,) configuration.
            v: (nv,) velocity.
            tau: (nv,) joint efforts (N m or N).
            settings: Pinocchio's proximal settings (`proximal_settings`); its outcome is written back.

        Returns:
            (nv,) accelerations (copy them before the next call, as those of `dynamics`).
        """
        assert self.ordered, "a data not set up for lcaba"
        return pin.lcaba(self.model, self.data, q, v, tau, self.models, self.datas, settings)

    def jacobian(self) -> np.ndarray:
        """(rows, nv) the anchors' constraint Jacobian at the last call's state (fresh after either call)."""
        J = pin.getConstraintsJacobian(self.model, self.data, self.models, self.datas)
        return J if J.ndim == 2 else J.reshape(-1, self.model.nv)  # Pinocchio gives a vector when rows or nv is 1

    def drift(self, rows: int) -> np.ndarray:
        """The anchors' drift at the last `dynamics` call's state.

        Args:
            rows: how many anchor rows to read.

        Returns:
            (rows,) gamma (+ Baumgarte terms).
        """
        return -self._rhs[:rows]

    def lcaba_error(self) -> np.ndarray:
        """(rows,) the anchors' acceleration error before lcaba's last step (add J @ `last_step()`)."""
        parts = [cd.contact_acceleration_error.vector[:k] for cd, k in zip(self.datas, self.sizes)]
        return np.concatenate(parts) if parts else np.zeros(0)

    def last_step(self) -> np.ndarray:
        """(nv,) lcaba's last acceleration step (`data.g`)."""
        return self.data.g


def expresses(cuts: list[CutRows], couplings: int) -> bool:
    """Whether the legacy constraint models express these cuts and couplings ("proximal" and "lcaba" can run).

    Args:
        cuts: the cuts.
        couplings: number of coupling rows.

    Returns:
        False for a coupling row or a Hooke or prismatic cut, else True.
    """
    return not couplings and all(cut.closure.kind not in _INEXPRESSIBLE for cut in cuts)


#: Cut kinds no legacy constraint model expresses.
_INEXPRESSIBLE = ("hooke", "prismatic")


def proximal_settings(accuracy: float, mu: float, max_iter: int) -> pin.ProximalSettings:
    """Pinocchio's proximal settings.

    Args:
        accuracy: absolute accuracy.
        mu: proximal regularisation.
        max_iter: iteration limit.

    Returns:
        A new `pin.ProximalSettings`.
    """
    return pin.ProximalSettings(accuracy, mu, max_iter)


def settings_outcome(settings: pin.ProximalSettings) -> tuple[float, int]:
    """What Pinocchio reports after a call with these settings.

    Args:
        settings: the settings passed to the call.

    Returns:
        (absolute residual, iterations).
    """
    return float(settings.absolute_residual), int(settings.iter)


def _ground_side_second(model: pin.Model, cm: pin.RigidConstraintModel) -> pin.RigidConstraintModel:
    """The same constraint with its sides swapped when its first side is the universe: Pinocchio 4.1's
    `lcaba` ends the process (a segmentation fault) on a constraint whose `joint1_id` is 0. The swap
    leaves the accelerations unchanged (the rows only change sign), and mechkit takes lcaba's constraint
    force from them (`rnea(a) - tau`), not from its multipliers."""
    if cm.joint1_id != 0:
        return cm
    return pin.RigidConstraintModel(
        cm.type, model, cm.joint2_id, cm.joint2_placement, cm.joint1_id, cm.joint1_placement, cm.reference_frame
    )


def _legacy_models(model: pin.Model, cuts: list[CutRows]) -> list[pin.RigidConstraintModel]:
    out = []
    for cut in cuts:
        c = cut.closure
        fa, fb = model.frames[cut.frame_a], model.frames[cut.frame_b]
        if c.kind == "weld":
            out.append(
                pin.RigidConstraintModel(
                    pin.ContactType.CONTACT_6D,
                    model,
                    fa.parentJoint,
                    fa.placement,
                    fb.parentJoint,
                    fb.placement,
                    pin.ReferenceFrame.LOCAL,
                )
            )
            continue
        if c.kind in _INEXPRESSIBLE:
            raise MethodUnavailable(
                "pin.constraintDynamics",
                f"cut {c.name!r} is {c.kind}: no RigidConstraintModel expresses it; the kkt and nullspace methods do",
            )
        offsets = [np.zeros(3)]
        if c.kind == "revolute" and c.rows != "planar":
            offsets.append(AXIS_ANCHOR_OFFSET * c.axis)
        for offset in offsets:
            pa = fa.placement * pin.SE3(np.eye(3), offset)
            pb = fb.placement * pin.SE3(np.eye(3), offset)
            out.append(
                pin.RigidConstraintModel(
                    pin.ContactType.CONTACT_3D, model, fa.parentJoint, pa, fb.parentJoint, pb, pin.ReferenceFrame.LOCAL
                )
            )
    return out
