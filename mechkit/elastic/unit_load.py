"""A second opinion on the compliant reactions: the SOC virtual-work solution made compatible by the
unit-load method (Castigliano), written apart from `mechkit.elastic.statics`.

1. The SOC second opinion (`mechkit.second_opinion`) gives one equilibrium R_p at the instant (its own
   convention where its SKCs leave components free).
2. The self-stresses come from the bodies' Newton-Euler equilibrium written here from the geometry:
   unknowns the joints' constrained components (a revolute: forces and the moments normal to its axis
   from the URDF; an actuator locked: all six), six equations per moving body.
3. For every pair of states, the unit-load integral over every beam,
   delta_ik = int (N_i N_k / EA + T_i T_k / GJ + M1_i M1_k / EI1 + M2_i M2_k / EI2) ds,
   the resultants along a beam following from the end wrench at its joint (Simpson's rule: exact for
   these quadratic integrands), plus u_i u_k / k for an actuator on a drive stiffness.
4. Castigliano: the redundants X solve delta X = -delta_0; R = R_p + sum X_k r_k.

Joint stiffness (`JointElasticity.stiffness`) is not taken: this method covers beams and drives.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin
import scipy.linalg

from mechkit.base.exceptions import MethodUnavailable
from mechkit.elastic.sections import ElasticData
from mechkit.elastic.urdf_elements import parse_elastic
from mechkit.mechanism import Mechanism
from mechkit.second_opinion.opinion import SecondOpinion


def _basis(axis: np.ndarray | None, kind: str, locked: bool) -> np.ndarray:
    """(6, r) orthonormal constrained wrench directions of a joint at its point (world)."""
    if locked or kind == "weld":
        return np.eye(6)
    if kind == "spherical":
        return np.vstack([np.eye(3), np.zeros((3, 3))])
    W = np.zeros((6, 5 if kind == "revolute" else 4))
    W[:3, :3] = np.eye(3)
    if kind == "revolute":
        W[3:, 3:] = scipy.linalg.null_space(axis[None])
    else:  # hooke: the moment about the normal of its two axes
        W[3:, 3] = axis / np.linalg.norm(axis)
    return W


def _moment_about_origin(w: np.ndarray, point: np.ndarray) -> np.ndarray:
    """(6, k) wrenches about `point` re-expressed about the world origin."""
    out = w.copy()
    out[3:] += np.cross(point, w[:3].T).T
    return out


class UnitLoad:
    """The unit-load method on one mechanism (actuators locked unless a drive stiffness is given).

    Raises:
        MethodUnavailable: a joint stiffness in the elastic data (not covered here).
    """

    def __init__(self, mech: Mechanism, data: ElasticData | None = None):
        self.mech = mech
        self.data = parse_elastic(mech.urdf) if data is None else data
        if any(j.stiffness is not None for j in self.data.joints.values()):
            raise MethodUnavailable("unit-load method", "joint stiffness is not covered: only beams and drives")
        self.opinion = SecondOpinion(mech)
        root = ET.fromstring(mech.urdf)
        self.axes = {
            j.get("name"): np.array([float(x) for x in j.find("axis").get("xyz").split()])
            for j in root.findall("joint")
            if j.find("axis") is not None
        }

    def _joints(self, pdata: pin.Data) -> list[dict]:
        """Every joint (tree, then cuts): sides, point, centre, constrained directions (world)."""
        model, out = self.mech.model, []
        for j in range(1, model.njoints):
            name = model.names[j]
            axis = pdata.oMi[j].rotation @ self.axes[name] if name in self.axes else None
            out.append((name, model.parents[j], j, pdata.oMi[j].translation.copy(), axis, "revolute"))
        for c in self.mech.closures:
            fa, fb = model.getFrameId(c.frame_a), model.getFrameId(c.frame_b)
            axis = pdata.oMf[fa].rotation @ c.axis if c.axis is not None else None
            if c.kind == "hooke":
                axis = np.cross(pdata.oMf[fa].rotation @ c.axis_a, pdata.oMf[fb].rotation @ c.axis_b)
            out.append(
                (
                    c.name,
                    model.frames[fa].parentJoint,
                    model.frames[fb].parentJoint,
                    pdata.oMf[fb].translation.copy(),
                    axis,
                    c.kind,
                )
            )
        joints = []
        for name, a, b, point, axis, kind in out:
            offset = self.data.joints[name].centre if name in self.data.joints else 0.0
            centre = point + (offset * axis / np.linalg.norm(axis) if offset else 0.0)
            joints.append(
                {
                    "name": name,
                    "a": a,
                    "b": b,
                    "point": point,
                    "centre": centre,
                    "axis": axis,
                    "W": _basis(axis, kind, name in self.mech.actuated),
                }
            )
        return joints

    def reactions(self, q: np.ndarray, v: np.ndarray, a: np.ndarray) -> dict[str, np.ndarray]:
        """The compatible reactions at one instant of a motion.

        Args:
            q: (nq,) configuration closing the loops.
            v: (nv,) velocities.
            a: (nv,) accelerations.

        Returns:
            Joint name (tree joints, then cuts) -> reaction (6,) [f (N), m (N m) about its point], world axes.
        """
        model = self.mech.model
        pdata = model.createData()
        pin.framesForwardKinematics(model, pdata, q)
        joints = self._joints(pdata)
        opinion = self.opinion.solve(q, v, a)
        Rp = np.array([opinion.reactions[j["name"]] for j in joints])
        # self-stresses of the bodies' equilibrium (6 per moving body, about the world origin)
        sizes = [j["W"].shape[1] for j in joints]
        starts = np.cumsum([0] + sizes)
        E = np.zeros((6 * (model.njoints - 1), starts[-1]))
        for k, j in enumerate(joints):
            on_origin = _moment_about_origin(j["W"], j["point"])
            for body, sign in ((j["b"], 1.0), (j["a"], -1.0)):
                if body:
                    E[6 * (body - 1) : 6 * body, starts[k] : starts[k + 1]] += sign * on_origin
        N = scipy.linalg.null_space(E)
        states = np.zeros((N.shape[1], len(joints), 6))
        for k, j in enumerate(joints):
            states[:, k] = (j["W"] @ N[starts[k] : starts[k + 1]]).T
        every = np.concatenate([Rp[None], states])  # state 0: the SOC equilibrium; then the unit self-stresses
        delta = self._flexibility(pdata, joints, every)
        X = -np.linalg.lstsq(delta[1:, 1:], delta[1:, 0], rcond=1e-12)[0]
        R = Rp + np.tensordot(X, states, axes=1)
        return {j["name"]: R[k] for k, j in enumerate(joints)}

    def _flexibility(self, pdata: pin.Data, joints: list[dict], states: np.ndarray) -> np.ndarray:
        """(S, S) unit-load integrals between the reaction states (S, n_joints, 6)."""
        model = self.mech.model
        count = np.zeros(model.njoints, dtype=int)
        for j in joints:
            count[j["a"]] += 1
            count[j["b"]] += 1
        bodies = {f.name: f.parentJoint for f in model.frames if f.type == pin.FrameType.BODY}
        delta = np.zeros((len(states), len(states)))
        for link, s in self.data.sections.items():
            body = bodies[link]
            if not body or not 1 <= count[body] <= 2:
                continue
            com = pdata.oMi[body].act(model.inertias[body].lever)
            frame = model.frames[model.getFrameId(link)]
            axis1 = pdata.oMi[body].rotation @ frame.placement.rotation @ s.axis1
            for k, j in enumerate(joints):
                if body not in (j["a"], j["b"]):
                    continue
                sign = 1.0 if body == j["b"] else -1.0
                length = np.linalg.norm(com - j["centre"])
                if length < 1e-12:
                    continue
                e = (com - j["centre"]) / length
                y = axis1 - (axis1 @ e) * e
                y /= np.linalg.norm(y)
                z = np.cross(e, y)
                f = sign * states[:, k, :3]
                m_centre = sign * (states[:, k, 3:] + np.cross(j["point"] - j["centre"], states[:, k, :3]))
                for weight, at in ((1.0, 0.0), (4.0, 0.5), (1.0, 1.0)):  # Simpson over s = at * length
                    m = m_centre - at * length * np.cross(e, f)
                    parts = np.stack(
                        [
                            f @ e / np.sqrt(s.E * s.A),
                            m @ e / np.sqrt(s.G * s.J),
                            m @ y / np.sqrt(s.E * s.I1),
                            m @ z / np.sqrt(s.E * s.I2),
                        ],
                        axis=1,
                    )
                    delta += weight * length / 6.0 * parts @ parts.T
        for name, j in self.data.joints.items():
            if j.drive is not None:
                k = [jt["name"] for jt in joints].index(name)
                axis = joints[k]["axis"] / np.linalg.norm(joints[k]["axis"])
                u = states[:, k, 3:] @ axis
                delta += np.outer(u, u) / j.drive
        return delta
