"""Large closed-loop models: a ladder of N four-bar loops, and loop-constrained ABA for its forward dynamics.

The ladder (values ours, a test model): two rails of N bars (length `RAIL` m, along +z at q = 0),
the left one at x = 0, the right one at x = `RUNG`; on top of left bar i a rung (length `RUNG` m,
along +x), pinned at its far end to the top of right bar i by a planar revolute cut. Every bar is a
uniform rod of `MASS` kg. Loop i is the four-bar (rung i-1 or the ground, left bar i, rung i, right
bar i): 3N joints, 2N independent rows, N degrees of freedom; q = 0 is assembled (rectangles).

`LoopConstrainedABA` is Pinocchio's loop-constrained articulated-body algorithm (`pin.lcaba`, with
the joint elimination order of `pin.computeJointMinimalOrdering` computed once) on the legacy
`RigidConstraintModel`s of `Mechanism.pin_constraints` (same sign convention as
`pin.constraintDynamics`: M a + nle = tau + J^T lambda): an augmented Lagrangian whose every
iteration is one O(n) sweep, where `constraintDynamics` factorises the constrained system with
fill-in. Its result is certified by Pinocchio's own closure residual on the final accelerations
(max |J a + gamma| over the anchors), or refused (`ClosureNotConverged`): on mechanisms where lcaba
does not converge (measured: tetra_3rr3uru, deployable_9rr12uru) it raises, never
returns a wrong answer.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit.base import arguments
from mechkit.base.exceptions import ClosureNotConverged, InvalidParameters, SingularConfiguration
from mechkit.core import forward
from mechkit.loading import from_urdf
from mechkit.mechanism import Mechanism

#: Rail bar and rung lengths (m) and the mass of every bar (kg) of the ladder (ours).
RAIL, RUNG, MASS = 0.2, 0.3, 0.1
#: lcaba's settings (mu, accuracy, max_iter), measured on the ladder and the registered mechanisms:
#: mu in units of the model's Delassus scale (`forward.delassus_scale`; lcaba's penalty is 1 / mu), the
#: accuracy on the closure accelerations (m/s^2 for point anchors). A small mu converges in fewer
#: iterations but amplifies rounding (at mu = 0.01: 4e-9 relative error on 64 loops, 5 iterations); at
#: 1: 6e-11 in 31 iterations on 64 loops; against the dense KKT 3e-11 or better in 16 to 82
#: iterations on four_bar, five_bar, parallel_2t1r and ten_bar (3e-10 on spherical_2dof, 180 iterations).
LCABA_DEFAULTS = (1.0, 1e-10, 200)


def _rod(name: str, length: float, axis: int) -> str:
    """A uniform rod link from its frame origin along +x (axis 0) or +z (axis 2)."""
    c = [0.0, 0.0, 0.0]
    c[axis] = length / 2
    end = MASS * length**2 / 12
    inertia = [end, end, end]
    inertia[axis] = MASS * 1e-6  # thin rod: a small axial inertia keeps the inertia positive definite
    return (f'<link name="{name}"><inertial><origin xyz="{c[0]} {c[1]} {c[2]}" rpy="0 0 0"/><mass value="{MASS}"/>'
            f'<inertia ixx="{inertia[0]}" ixy="0" ixz="0" iyy="{inertia[1]}" iyz="0" izz="{inertia[2]}"/></inertial></link>')


def _joint(name: str, parent: str, child: str, xyz: tuple[float, float, float], kind: str = "revolute") -> str:
    axis = '<axis xyz="0 1 0"/><limit effort="1e6" lower="-25" upper="25" velocity="1e3"/>' if kind == "revolute" else ""
    return (f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
            f'<origin xyz="{xyz[0]} {xyz[1]} {xyz[2]}" rpy="0 0 0"/>{axis}</joint>')


def ladder_urdf(n: int) -> str:
    """URDF text of the ladder of n four-bar loops, closed by `<mechkit:loop>` cuts.

    Raises:
        InvalidParameters: n < 1.
    """
    if int(n) != n or n < 1:
        raise InvalidParameters("n", n, "the ladder needs a whole number of loops >= 1")
    parts = ['<robot name="ladder" xmlns:mechkit="https://mechkit.dev/loop">', '<link name="ground"/>']
    for i in range(1, n + 1):
        left_parent, right_parent = ("ground", "ground") if i == 1 else (f"left_{i - 1}", f"right_{i - 1}")
        base = 0.0 if i == 1 else RAIL
        parts += [_rod(f"left_{i}", RAIL, 2), _rod(f"right_{i}", RAIL, 2), _rod(f"rung_{i}", RUNG, 0),
                  _joint(f"l{i}", left_parent, f"left_{i}", (0.0, 0.0, base)),
                  _joint(f"r{i}", right_parent, f"right_{i}", (RUNG if i == 1 else 0.0, 0.0, base)),
                  _joint(f"g{i}", f"left_{i}", f"rung_{i}", (0.0, 0.0, RAIL)),
                  f'<link name="rung_{i}_end"/>', _joint(f"rung_{i}_end_fixed", f"rung_{i}", f"rung_{i}_end", (RUNG, 0.0, 0.0), "fixed"),
                  f'<link name="right_{i}_top"/>', _joint(f"right_{i}_top_fixed", f"right_{i}", f"right_{i}_top", (0.0, 0.0, RAIL), "fixed"),
                  (f'<mechkit:loop name="c{i}" type="revolute" rows="planar" axis="0 1 0" frame_a="rung_{i}_end" '
                  f'frame_b="right_{i}_top"/>')]
    parts.append("</robot>")
    return "\n".join(parts)


def ladder(n: int) -> Mechanism:
    """The ladder of n four-bar loops as a Mechanism, actuated at the left rail's joints, home at q = 0."""
    return from_urdf(ladder_urdf(n), actuated=[f"l{i}" for i in range(1, n + 1)], name=f"ladder_{n}")


class LoopConstrainedABA:
    """Forward dynamics by `pin.lcaba` on a mechanism's constraint models (set up once).

    Args:
        mech: a mechanism whose cuts Pinocchio's legacy constraints express (`Mechanism.pin_constraints`).
        mu: penalty compliance, in units of the model's Delassus scale at home (must be > 0; see
            `LCABA_DEFAULTS`).
        accuracy: largest closure acceleration error of a result (m/s^2 for point anchors).
        max_iter: iteration limit.

    Raises:
        InvalidArgument: mu or accuracy not > 0, max_iter below 1.
        MethodUnavailable: a cut no legacy constraint expresses (Hooke, prismatic).
    """

    def __init__(self, mech: Mechanism, mu: float = LCABA_DEFAULTS[0], accuracy: float = LCABA_DEFAULTS[1],
                 max_iter: int = LCABA_DEFAULTS[2]):
        mu, accuracy = arguments.number("mu", mu, positive=True), arguments.number("accuracy", accuracy, positive=True)
        max_iter = arguments.integer("max_iter", max_iter, minimum=1)
        self.model, self.nq = mech.model, mech.model.nq
        cms, _ = mech.pin_constraints()
        self.cms = cms
        self.cds = pin.StdVec_RigidConstraintData()
        for cm in cms:
            self.cds.append(cm.createData())
        self.data = self.model.createData()
        pin.computeJointMinimalOrdering(self.model, self.data, self.cms)
        J = mech.closure_jacobian(mech.home_q)
        scale = forward.delassus_scale(pin.crba(self.model, self.model.createData(), mech.home_q), J)
        # lcaba stops when the closure error, or else the last step |delta a|, falls below its one accuracy;
        # it is given accuracy / max |J_i| (at home), so that a step stop leaves J delta a within about
        # `accuracy` (the final residual is checked against `accuracy` itself, see __call__)
        lever = max(float(np.max(np.linalg.norm(J, axis=1), initial=0.0)), 1.0)
        self.accuracy = accuracy
        self.prox = pin.ProximalSettings(accuracy / lever, mu * scale, max_iter)

    def __call__(self, q: np.ndarray, v: np.ndarray, tau: np.ndarray) -> np.ndarray:
        """Accelerations (nv,) under joint efforts tau (nv,) at (q (nq,), v (nv,)).

        Raises:
            InvalidArgument: a malformed state (one sample only).
            SingularConfiguration: non-finite accelerations.
            ClosureNotConverged: the closure acceleration error is above the accuracy after the
                iterations (lcaba stopped on a vanishing step, or at max_iter).
        """
        nv = self.model.nv
        if not forward.plain_state(q, v, tau, self.nq, nv):
            q, v, tau = (arguments.array(name, x, n, batch=False) for name, x, n in (("q", q, self.nq), ("v", v, nv), ("tau", tau, nv)))
        a = pin.lcaba(self.model, self.data, q, v, tau, self.cms, self.cds, self.prox).copy()
        if not np.all(np.isfinite(a)):
            raise SingularConfiguration(float("inf"), "pin.lcaba returned non-finite accelerations")
        residual = self.prox.absolute_residual
        if not residual <= self.prox.absolute_accuracy:
            # lcaba measured the error before its last step g (data.g): the final one is that plus J g
            J = pin.getConstraintsJacobian(self.model, self.data, self.cms, self.cds)
            before = np.concatenate([cd.contact_acceleration_error.vector[:3 if cm.type == pin.ContactType.CONTACT_3D else 6]
                                     for cm, cd in zip(self.cms, self.cds)])
            residual = float(np.max(np.abs(before + J @ self.data.g), initial=0.0))
        if not residual <= self.accuracy:
            raise ClosureNotConverged(residual, self.accuracy, self.prox.iter, "pin.lcaba: closure accelerations J a + gamma")
        return a
