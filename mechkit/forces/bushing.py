"""Drake's LinearBushingRollPitchYaw between two frames A and C: a compliant bushing, for a
`drake:linear_bushing_rpy` loaded with `bushings="compliant"` (`mechkit.sources.drake_elements`).

The law is Drake's (drake/multibody/tree/linear_bushing_roll_pitch_yaw.h). Frame B is halfway between A
and C: its origin Bo the midpoint of Ao and Co, its orientation R_AB the half of R_AC's angle-axis.
With q = [q0 q1 q2] the roll-pitch-yaw angles of R_AC (R_AC = Rz(q2) Ry(q1) Rx(q0)) and r = p_AoCo
expressed in B, [x y z],

    tau = -K012 q - D012 q_dot,      f_B = -Kxyz [x y z] - Dxyz d/dt_B [x y z],

the gimbal torques tau (N m) and the force f (N, in B). C receives the force f at Bo and the torque
t = N^T tau (in A; q_dot = N w_AC, w_AC expressed in A); A receives -f at Bo and -t. The power of the
pair is tau . q_dot + f_B . d/dt_B [x y z], so the stiffness part has the potential
(K012 . q^2 + Kxyz . [x y z]^2) / 2 (J) and the damping part dissipates (Drake does not implement this
potential; it follows from the law). At a pitch within `GIMBAL` of +-pi/2 the law is singular (Drake
throws there too), and past it roll and yaw jump by pi (Drake's angles are in (-pi, pi] x [-pi/2, pi/2] x
(-pi, pi]), so does a stiff roll or yaw's torque: a bushing standing for a pin should leave yaw free, as
Drake's Strandbeest does, not pitch.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import InvalidParameters, SingularConfiguration
from mechkit.forces.element import ForceElement, ForceState, Load, wrench_on_body
from mechkit.sources.drake_elements import Bushing

#: |cos(pitch)| under which the roll-pitch-yaw rates are undefined (ours; Drake's gimbal-lock check).
GIMBAL = 1e-9


class BushingForce(ForceElement):
    """One compliant bushing on a model: frame A is the cut frame `<name>_a`, C is `<name>_b`.

    Args:
        model: the tree's Pinocchio model (with the bushing's frames).
        bushing: the bushing's data.

    Raises:
        InvalidParameters: the model lacks its frames.
    """

    def __init__(self, model: pin.Model, bushing: Bushing):
        self.bushing, self.name = bushing, bushing.name
        self.role = "dissipative" if np.any(bushing.torque_damping) or np.any(bushing.force_damping) else "conservative"
        self._frames = []
        for side in "ab":
            frame = f"{bushing.name}_{side}"
            if not model.existFrame(frame):
                raise InvalidParameters(f"{bushing.name} frame", frame, "the model has no such frame")
            self._frames.append(model.getFrameId(frame))

    def _pose(self, model: pin.Model, data: pin.Data) -> tuple[pin.SE3, pin.SE3, np.ndarray, np.ndarray]:
        """X_WA, X_WC, R_AC and p_AoCo in A, from the joint placements in `data`."""
        oA, oC = (pin.updateFramePlacement(model, data, f) for f in self._frames)
        return oA, oC, oA.rotation.T @ oC.rotation, oA.rotation.T @ (oC.translation - oA.translation)

    def deflection(self, model: pin.Model, data: pin.Data) -> dict[str, np.ndarray]:
        """The bushing's kinematics at the state in `data`.

        Args:
            model: the tree's Pinocchio model.
            data: its data after `forwardKinematics(q, v)`.

        Returns:
            "q" (3,) roll, pitch, yaw (rad); "q_dot" (3,) their rates; "xyz" (3,) p_AoCo in B (m); "xyz_dot"
            (3,) its rate in B; "R_WA", "R_AB" (3, 3); "p_WBo" (3,) Bo in the world (m).

        Raises:
            SingularConfiguration: the pitch is at gimbal lock.
        """
        oA, oC, R_AC, p_AoCo_A = self._pose(model, data)
        vA, vC = (pin.getFrameVelocity(model, data, f, pin.LOCAL_WORLD_ALIGNED) for f in self._frames)
        R_WA = oA.rotation
        w_AC_A = R_WA.T @ (vC.angular - vA.angular)
        v_ACo_A = R_WA.T @ (vC.linear - vA.linear - np.cross(vA.angular, oC.translation - oA.translation))
        q = pin.rpy.matrixToRpy(R_AC)
        c1 = math.cos(q[1])
        if abs(c1) < GIMBAL:
            raise SingularConfiguration(math.inf, f"bushing {self.name!r} at gimbal lock (pitch {q[1]:.6g} rad)")
        s2, c2, t1 = math.sin(q[2]), math.cos(q[2]), math.tan(q[1])
        N = np.array([[c2 / c1, s2 / c1, 0.0], [-s2, c2, 0.0], [c2 * t1, s2 * t1, 1.0]])
        R_AB = pin.exp3(0.5 * pin.log3(R_AC))
        return {
            "q": q,
            "q_dot": N @ w_AC_A,
            "N": N,
            "xyz": R_AB.T @ p_AoCo_A,
            "xyz_dot": R_AB.T @ (v_ACo_A - np.cross(0.5 * w_AC_A, p_AoCo_A)),
            "R_WA": R_WA,
            "R_AB": R_AB,
            "p_WBo": 0.5 * (oA.translation + oC.translation),
        }

    def load(self, state: ForceState) -> Load:
        """The bushing's force and torque on both bodies as `fext` rows, and the damping's power.

        Args:
            state: the state (frame placements and joint velocities are read).

        Returns:
            The `Load`: body wrenches (njoints, 6); the power (W, <= 0) of the damping.

        Raises:
            SingularConfiguration: the pitch is at gimbal lock.
        """
        b, model, data = self.bushing, state.model, state.data
        k = self.deflection(model, data)
        tau_d, f_d = -b.torque_damping * k["q_dot"], -b.force_damping * k["xyz_dot"]
        tau = -b.torque_stiffness * k["q"] + tau_d
        f_B = -b.force_stiffness * k["xyz"] + f_d
        torque = k["R_WA"] @ (k["N"].T @ tau)
        force = k["R_WA"] @ (k["R_AB"] @ f_B)
        out = np.zeros((model.njoints, 6))
        for frame, sign in zip(self._frames, (-1.0, 1.0)):
            joint = model.frames[frame].parentJoint
            if joint:
                out[joint] += wrench_on_body(model, data, joint, sign * force, sign * torque, k["p_WBo"])
        return Load(None, out, float(tau_d @ k["q_dot"] + f_d @ k["xyz_dot"]))

    def energy(self, model: pin.Model, data: pin.Data, q: np.ndarray) -> float:
        """The stiffness's potential at q.

        Args:
            model: the tree's Pinocchio model.
            data: its data after `forwardKinematics(q)`.
            q: (nq,) configuration (unused: `data` has it).

        Returns:
            (K012 . q^2 + Kxyz . [x y z]^2) / 2 (J).

        Raises:
            SingularConfiguration: the pitch is at gimbal lock.
        """
        b = self.bushing
        _, _, R_AC, p_AoCo_A = self._pose(model, data)
        xyz = pin.exp3(0.5 * pin.log3(R_AC)).T @ p_AoCo_A
        rpy = pin.rpy.matrixToRpy(R_AC)
        return 0.5 * float(b.torque_stiffness @ rpy**2 + b.force_stiffness @ xyz**2)


def bushing_forces(model: pin.Model, bushings: Sequence[Bushing]) -> list[BushingForce]:
    """Force elements of compliant bushings.

    Args:
        model: the tree's Pinocchio model (with each bushing's frames `<name>_a`, `<name>_b`).
        bushings: the bushings (`mechkit.sources.drake_elements.Bushing`).

    Returns:
        One `BushingForce` each.

    Raises:
        InvalidParameters: a frame the model does not have.
    """
    return [BushingForce(model, b) for b in bushings]
