"""MuJoCo's own numbers on an MJCF file, for the independent check of mechkit's MJCF reader.

Everything here comes from MuJoCo's functions on the same file (mj_forward): the equality rows
(`efc_pos`, `efc_J`), the bias and passive forces, the actuator moments, the compiled inertias. The
only link to the reader's model is the joint names and MuJoCo's documented coordinates (a ball's and a
free joint's quaternion w, x, y, z; a free joint's linear velocity in the world frame, its angular
velocity in the body frame, as Pinocchio's ball; Pinocchio's free-flyer takes both in the body frame).
"""

from __future__ import annotations

from pathlib import Path

import mujoco
import numpy as np
import pinocchio as pin

FREE, BALL = 0, 1


class MujocoReference:
    """A compiled MJCF file and the map between its coordinates and a Pinocchio model's (by joint name)."""

    def __init__(self, path: Path, model: pin.Model):
        self.mm = mujoco.MjModel.from_xml_path(str(path))
        self.mm.opt.jacobian = mujoco.mjtJacobian.mjJAC_DENSE
        self.mm.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT | mujoco.mjtDisableBit.mjDSBL_LIMIT
        self.md = mujoco.MjData(self.mm)
        self.model = model
        self.joints = [
            (mujoco.mj_id2name(self.mm, mujoco.mjtObj.mjOBJ_JOINT, j) or f"joint{j}", j) for j in range(self.mm.njnt)
        ]

    def qpos(self, q: np.ndarray) -> np.ndarray:
        """MuJoCo's qpos of the Pinocchio configuration q."""
        out = self.mm.qpos0.copy()
        for name, j in self.joints:
            pj = self.model.joints[self.model.getJointId(name)]
            a, iq = int(self.mm.jnt_qposadr[j]), pj.idx_q
            kind = int(self.mm.jnt_type[j])
            if kind == FREE:
                out[a : a + 3] = q[iq : iq + 3]
                x, y, z, w = q[iq + 3 : iq + 7]
                out[a + 3 : a + 7] = (w, x, y, z)
            elif kind == BALL:
                x, y, z, w = q[iq : iq + 4]
                out[a : a + 4] = (w, x, y, z)
            else:
                out[a] = q[iq]
        return out

    def joint_values(self, qpos: np.ndarray) -> dict[str, float | tuple[float, ...]]:
        """MuJoCo's qpos as joint values (the form of `Description.guess`: a ball's rotation vector, a
        free joint's position and rotation vector)."""
        out: dict[str, float | tuple[float, ...]] = {}
        for name, j in self.joints:
            a, kind = int(self.mm.jnt_qposadr[j]), int(self.mm.jnt_type[j])
            if kind in (FREE, BALL):
                at = a + 3 if kind == FREE else a
                w, x, y, z = qpos[at : at + 4]
                rotation = tuple(pin.log3(pin.Quaternion(w, x, y, z).normalized().matrix()))
                out[name] = tuple(qpos[a : a + 3]) + rotation if kind == FREE else rotation
            else:
                out[name] = float(qpos[a])
        return out

    def velocity_map(self, q: np.ndarray) -> np.ndarray:
        """T with v_mujoco = T v_pinocchio at q (so generalised forces map as f_pinocchio = T^T f_mujoco)."""
        T = np.zeros((self.mm.nv, self.model.nv))
        for name, j in self.joints:
            pj = self.model.joints[self.model.getJointId(name)]
            d, iv, nv = int(self.mm.jnt_dofadr[j]), pj.idx_v, pj.nv
            T[d : d + nv, iv : iv + nv] = np.eye(nv)
            if int(self.mm.jnt_type[j]) == FREE:
                x, y, z, w = q[pj.idx_q + 3 : pj.idx_q + 7]
                T[d : d + 3, iv : iv + 3] = pin.Quaternion(w, x, y, z).normalized().matrix()
        return T

    def at(self, q: np.ndarray) -> dict[str, np.ndarray]:
        """MuJoCo's quantities at rest at q, forces and Jacobians mapped to Pinocchio's velocity order:
        residual (equality rows' efc_pos), J (equality rows of efc_J), generalised (qfrc_bias -
        qfrc_passive), moment (actuator moments, (nu, nv)), gear (each actuator's gear[0])."""
        self.md.qpos[:] = self.qpos(q)
        self.md.qvel[:] = 0.0
        mujoco.mj_forward(self.mm, self.md)
        T = self.velocity_map(q)
        rows = np.flatnonzero(self.md.efc_type[: self.md.nefc] == mujoco.mjtConstraint.mjCNSTR_EQUALITY)
        J = self.md.efc_J[: self.md.nefc * self.mm.nv].reshape(self.md.nefc, self.mm.nv)[rows]
        moment = np.zeros((self.mm.nu, self.mm.nv))
        mujoco.mju_sparse2dense(
            moment, self.md.actuator_moment, self.md.moment_rownnz, self.md.moment_rowadr, self.md.moment_colind
        )
        return {
            "residual": self.md.efc_pos[rows].copy(),
            "J": J @ T,
            "generalised": T.T @ (self.md.qfrc_bias - self.md.qfrc_passive),
            "moment": moment @ T,
            "gear": self.mm.actuator_gear[:, 0].copy(),
        }

    def efforts(self, q: np.ndarray, held: tuple[str, ...] = ()) -> tuple[np.ndarray, float]:
        """MuJoCo's own holding efforts at q: the least-squares solution of
        [moment^T, e_held, J_eq^T] [u; stops; lambda] = qfrc_bias - qfrc_passive, in MuJoCo's
        coordinates, and the norm of what is left unbalanced."""
        self.at(q)
        nv = self.mm.nv
        rows = np.flatnonzero(self.md.efc_type[: self.md.nefc] == mujoco.mjtConstraint.mjCNSTR_EQUALITY)
        J = self.md.efc_J[: self.md.nefc * nv].reshape(self.md.nefc, nv)[rows]
        moment = np.zeros((self.mm.nu, nv))
        mujoco.mju_sparse2dense(
            moment, self.md.actuator_moment, self.md.moment_rownnz, self.md.moment_rowadr, self.md.moment_colind
        )
        stops = np.zeros((len(held), nv))
        for i, name in enumerate(held):
            stops[i, self.mm.jnt_dofadr[mujoco.mj_name2id(self.mm, mujoco.mjtObj.mjOBJ_JOINT, name)]] = 1.0
        A = np.hstack([moment.T, stops.T, J.T])
        b = self.md.qfrc_bias - self.md.qfrc_passive
        x = np.linalg.lstsq(A, b, rcond=None)[0]
        return x[: self.mm.nu + len(held)], float(np.linalg.norm(A @ x - b))

    def in_our_units(self, u_mujoco: np.ndarray) -> np.ndarray:
        """MuJoCo's actuator forces (and, after them, stop forces) in the reader's convention: a joint
        motor's effort is its joint's generalised force (gear times MuJoCo's), a tendon motor's is MuJoCo's."""
        factor = np.where(np.isin(self.mm.actuator_trntype, (0, 1)), self.mm.actuator_gear[:, 0], 1.0)
        return u_mujoco * np.concatenate([factor, np.ones(len(u_mujoco) - self.mm.nu)])

    def inertias(self) -> dict[str, dict[str, object]]:
        """Compiled inertias by body: mass (kg), com (body frame, m), inertia about the com (body frame)."""
        out = {}
        for b in range(1, self.mm.nbody):
            R = np.empty(9)
            mujoco.mju_quat2Mat(R, self.mm.body_iquat[b])
            R = R.reshape(3, 3)
            out[mujoco.mj_id2name(self.mm, mujoco.mjtObj.mjOBJ_BODY, b)] = {
                "mass": float(self.mm.body_mass[b]),
                "com": self.mm.body_ipos[b].copy(),
                "inertia": R @ np.diag(self.mm.body_inertia[b]) @ R.T,
            }
        return out
