"""Large closed-loop models: a ladder of N four-bar loops, and loop-constrained ABA for its forward dynamics.

The ladder (values ours, a test model): two rails of N bars (length `RAIL` m, along +z at q = 0),
the left one at x = 0, the right one at x = `RUNG`; on top of left bar i a rung (length `RUNG` m,
along +x), pinned at its far end to the top of right bar i by a planar revolute cut. Every bar is a
uniform rod of `MASS` kg. Loop i is the four-bar (rung i-1 or the ground, left bar i, rung i, right
bar i): 3N joints, 2N independent rows, N degrees of freedom; q = 0 is assembled (rectangles).

`LoopConstrainedABA` is Pinocchio's loop-constrained articulated-body algorithm (`pin.lcaba`, with
the joint elimination order of `pin.computeJointMinimalOrdering` computed once) on the legacy
`RigidConstraintModel`s of `Mechanism.pin_constraints` (same sign convention as
`pin.constraintDynamics`: M a + nle = tau + J^T lambda). Its cost grows about linearly with the
number of loops, where `constraintDynamics` factorises the dense constrained system.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit.exceptions import InvalidParameters, SingularConfiguration
from mechkit.mechanism import Mechanism, from_urdf

#: Rail bar and rung lengths (m) and the mass of every bar (kg) of the ladder (ours).
RAIL, RUNG, MASS = 0.2, 0.3, 0.1
#: lcaba's proximal settings (mu, accuracy, max_iter), measured on the ladder: planar cuts have an
#: exactly-zero out-of-plane row in Pinocchio's 3D anchors, and a small mu amplifies rounding
#: (error ~ eps / mu: 5e-8 at mu = 1e-2 on 64 loops); mu = 10 converges in about 30 iterations to 8e-11.
LCABA_DEFAULTS = (10.0, 1e-12, 100)


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
        mu: proximal regularisation (must be positive; see `LCABA_DEFAULTS`).
        accuracy: proximal stopping tolerance.
        max_iter: proximal iteration limit.
    """

    def __init__(self, mech: Mechanism, mu: float = LCABA_DEFAULTS[0], accuracy: float = LCABA_DEFAULTS[1],
                 max_iter: int = LCABA_DEFAULTS[2]):
        self.model = mech.model
        cms, _ = mech.pin_constraints()
        self.cms = cms
        self.cds = pin.StdVec_RigidConstraintData()
        for cm in cms:
            self.cds.append(cm.createData())
        self.data = self.model.createData()
        pin.computeJointMinimalOrdering(self.model, self.data, self.cms)
        self.prox = pin.ProximalSettings(accuracy, mu, max_iter)

    def __call__(self, q: np.ndarray, v: np.ndarray, tau: np.ndarray) -> np.ndarray:
        """Accelerations (nv,) under joint efforts tau (nv,) at (q, v).

        Raises:
            SingularConfiguration: non-finite accelerations.
        """
        a = pin.lcaba(self.model, self.data, q, v, tau, self.cms, self.cds, self.prox).copy()
        if not np.all(np.isfinite(a)):
            raise SingularConfiguration(float("inf"), "pin.lcaba returned non-finite accelerations")
        return a
