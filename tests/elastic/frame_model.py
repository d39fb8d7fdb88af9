"""An independent finite-element frame model of a mechanism at a pose, for the elastic tests.

Built from the mechanism's geometry (Pinocchio placements at the pose, the URDF's joint axes and
loop records) and its elastic data, with PyNiteFEA: every beam of the idealisation is a PyNite member
(Euler-Bernoulli frame element; PyNite assembles the global stiffness), every rigid body one node at its
centre of mass, every joint a set of linear constraint equations between the two sides' displacements
at the joint's centre, solved by Lagrange multipliers (the reactions) here. Each member's global
stiffness comes from a PyNite model of its own (PyNite splits a member at any node lying on it, and the
two sides of a joint share their centre); the assembly, constraints and solve are this file's. Nothing of
`mechkit.elastic` but the reading of the section data is used. Sections must have I1 = I2 (tubes,
square bars): PyNite's member orientation then does not matter.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin
import scipy.linalg
from Pynite import Analysis, FEModel3D

from mechkit.elastic import parse_elastic


def _transport(r: np.ndarray) -> np.ndarray:
    """(6, 6) twist at a point r away from a node, from the node's twist [du, dtheta]: du + dtheta x r."""
    T = np.eye(6)
    T[:3, 3:] = -np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])
    return T


def _normals(a: np.ndarray) -> np.ndarray:
    """(3, 2) two unit vectors normal to a and to each other."""
    helper = np.array([1.0, 0.0, 0.0]) if abs(a[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    n1 = np.cross(a, helper)
    n1 /= np.linalg.norm(n1)
    return np.stack([n1, np.cross(a, n1)], axis=1)


def member_stiffness(i: np.ndarray, j: np.ndarray, s) -> np.ndarray:
    """(12, 12) global stiffness of one PyNite frame member from node i to node j (m), section s: a model
    of its own (PyNite splits a member at any other node lying on it, and joint centres coincide)."""
    assert np.isclose(s.I1, s.I2), "the frame model orients no member: I1 must equal I2"
    fe = FEModel3D()
    fe.add_node("i", *i)
    fe.add_node("j", *j)
    fe.add_material("m", s.E, s.G, s.E / (2 * s.G) - 1, 0.0)
    fe.add_section("s", s.A, s.I1, s.I2, s.J)
    fe.add_member("ij", "i", "j", "m", "s")
    Analysis._prepare_model(fe)
    return np.asarray(fe.Ke("Combo 1", sparse=False, check_stability=False))


class FrameModel:
    """The mechanism at pose q as a frame structure: beams, rigid bodies, joints; actuators locked."""

    def __init__(self, mech, q: np.ndarray, data=None):
        self.mech, self.q = mech, q
        model = mech.model
        self.data = data if data is not None else parse_elastic(mech.urdf)
        pdata = model.createData()
        pin.framesForwardKinematics(model, pdata, q)
        self.pdata = pdata
        root = ET.fromstring(mech.urdf)
        urdf_axes = {
            j.get("name"): np.array(
                [float(x) for x in (j.find("axis").get("xyz") if j.find("axis") is not None else "1 0 0").split()]
            )
            for j in root.findall("joint")
        }
        # joints: name, sides (a, b), centre (world), reporting point, constrained directions (6, r)
        self.joints = []
        for j in range(1, model.njoints):
            name = model.names[j]
            axis = pdata.oMi[j].rotation @ urdf_axes[name]
            origin = pdata.oMi[j].translation.copy()
            self.joints.append(
                self._joint(name, model.parents[j], j, origin, origin, axis, "revolute", pdata.oMi[j].rotation)
            )
        for c in mech.closures:
            fa, fb = model.getFrameId(c.frame_a), model.getFrameId(c.frame_b)
            axis = pdata.oMf[fa].rotation @ c.axis if c.axis is not None else None
            if c.kind == "hooke":
                axis = np.cross(pdata.oMf[fa].rotation @ c.axis_a, pdata.oMf[fb].rotation @ c.axis_b)
            origin = pdata.oMf[fb].translation.copy()
            self.joints.append(
                self._joint(
                    c.name,
                    model.frames[fa].parentJoint,
                    model.frames[fb].parentJoint,
                    origin,
                    origin,
                    axis,
                    c.kind,
                    pdata.oMf[fa].rotation,
                )
            )
        bodies_of = {f.name: f.parentJoint for f in model.frames if f.type == pin.FrameType.BODY}
        count = np.zeros(model.njoints, dtype=int)
        for jt in self.joints:
            count[jt["a"]] += 1
            count[jt["b"]] += 1
        self.sections = {
            bodies_of[link]: s
            for link, s in self.data.sections.items()
            if bodies_of[link] and 1 <= count[bodies_of[link]] <= 2
        }
        self._build(model, pdata)

    def _joint(self, name, a, b, origin, point, axis, kind, frame):
        """A joint: its sides, centre, constraint rows W (6, r) and spring (6, 6) on the sides' relative
        twist at the centre (world). A joint stiffness replaces the constraint rows by springs
        W_c (W_c^T K W_c) W_c^T, K the diagonal stiffness turned from the joint frame `frame` (3, 3) to
        the world; a drive stiffness replaces the lock of its axis by a spring."""
        elastic = self.data.joints.get(name)
        centre = origin + (elastic.centre * axis if elastic is not None else 0.0)
        free = np.zeros((6, 0))
        if kind == "weld":
            Wc = np.eye(6)
        elif kind == "revolute":
            a_ = axis / np.linalg.norm(axis)
            Wc = np.zeros((6, 5))
            Wc[:3, :3] = np.eye(3)
            Wc[3:, 3:] = _normals(a_)
            free = np.concatenate([np.zeros(3), a_])[:, None]
        elif kind == "spherical":
            Wc = np.vstack([np.eye(3), np.zeros((3, 3))])
        elif kind == "hooke":
            Wc = np.zeros((6, 4))
            Wc[:3, :3] = np.eye(3)
            Wc[3:, 3] = axis / np.linalg.norm(axis)
        else:
            raise NotImplementedError(kind)
        rows, spring = [], np.zeros((6, 6))
        if elastic is not None and elastic.stiffness is not None:
            R6 = scipy.linalg.block_diag(frame, frame)
            K = R6 @ np.diag(elastic.stiffness) @ R6.T
            spring += Wc @ (Wc.T @ K @ Wc) @ Wc.T
        else:
            rows.append(Wc)
        if name in self.mech.actuated:
            if elastic is not None and elastic.drive is not None:
                spring += elastic.drive * free @ free.T
            else:
                rows.append(free)
        W = np.hstack(rows) if rows else np.zeros((6, 0))
        return {"name": name, "a": a, "b": b, "centre": centre, "point": point, "W": W, "spring": spring}

    def _build(self, model, pdata):
        nodes: dict[str, np.ndarray] = {}
        self.com = {}
        for b in range(1, model.njoints):
            self.com[b] = pdata.oMi[b].act(model.inertias[b].lever)
            nodes[f"c{b}"] = self.com[b]
        self.ends = {}
        members = []
        for k, jt in enumerate(self.joints):
            for side in ("a", "b"):
                body = jt[side]
                if body in self.sections:
                    node = f"e{body}_{k}"
                    nodes[node] = jt["centre"]
                    self.ends[(body, k)] = node
                    members.append((f"c{body}", node, self.sections[body]))
        self.index = {name: i for i, name in enumerate(nodes)}
        self.ndof = 6 * len(nodes)
        self.K = np.zeros((self.ndof, self.ndof))
        for i, j, s in members:
            dofs = np.r_[6 * self.index[i] : 6 * self.index[i] + 6, 6 * self.index[j] : 6 * self.index[j] + 6]
            self.K[np.ix_(dofs, dofs)] += member_stiffness(nodes[i], nodes[j], s)
        rows = []
        self.slices = []
        for k, jt in enumerate(self.joints):
            jt["relative"] = self.side(jt["b"], k, jt["centre"]) - self.side(jt["a"], k, jt["centre"])
            self.K += jt["relative"].T @ jt["spring"] @ jt["relative"]
            block = jt["W"].T @ jt["relative"]
            self.slices.append(slice(len(rows), len(rows) + len(block)))
            rows.extend(block)
        self.C = np.array(rows).reshape(-1, self.ndof)

    def select(self, node: str) -> np.ndarray:
        out = np.zeros((6, self.ndof))
        i = 6 * self.index[node]
        out[:, i : i + 6] = np.eye(6)
        return out

    def side(self, body: int, k: int, point: np.ndarray) -> np.ndarray:
        """(6, ndof) the twist at `point` of body's side of joint k (its beam end, or the rigid body)."""
        if body == 0:
            return np.zeros((6, self.ndof))
        if (body, k) in self.ends:
            return self.select(self.ends[(body, k)])
        return _transport(point - self.com[body]) @ self.select(f"c{body}")

    def body(self, body: int, point: np.ndarray) -> np.ndarray:
        """(6, ndof) the twist of a body (its centre-of-mass node) at a point."""
        return _transport(point - self.com[body]) @ self.select(f"c{body}")

    def solve(self, f: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Displacements (ndof, k) and multipliers (rows, k) under nodal loads f (ndof, k)."""
        m = len(self.C)
        kkt = np.block([[self.K, self.C.T], [self.C, np.zeros((m, m))]])
        sol = np.linalg.solve(kkt, np.vstack([f, np.zeros((m, f.shape[1]))]))
        return sol[: self.ndof], sol[self.ndof :]

    def loads(self, fext: dict | None = None) -> np.ndarray:
        """(ndof, 1) the weights of every body at its centre of mass, plus world forces {body: (6,) at its CoM}."""
        f = np.zeros((self.ndof, 1))
        g = self.mech.model.gravity.linear
        for b in self.com:
            w = np.concatenate([self.mech.model.inertias[b].mass * g, np.zeros(3)])
            w += (fext or {}).get(b, np.zeros(6))
            f[:, 0] += self.select(f"c{b}").T @ w
        return f

    def reactions(self, f: np.ndarray) -> dict[str, np.ndarray]:
        """Joint name -> the wrench (6,) side a exerts on side b, about the reporting point, world."""
        d, mu = self.solve(f)
        out = {}
        for jt, rows in zip(self.joints, self.slices):
            w = -jt["W"] @ mu[rows, 0] - jt["spring"] @ jt["relative"] @ d[:, 0]
            offset = jt["centre"] - jt["point"]
            out[jt["name"]] = np.concatenate([w[:3], w[3:] + np.cross(offset, w[:3])])
        return out

    def compliance(self, body: int, point: np.ndarray) -> np.ndarray:
        """(6, 6) twist of a body at a point per unit wrench there (world axes)."""
        B = self.body(body, point)
        d, _ = self.solve(B.T)
        return B @ d

    def frequencies(self, n: int) -> np.ndarray:
        """The first n natural frequencies (Hz) with the bodies' masses and inertias at their CoM nodes."""
        M = np.zeros((self.ndof, self.ndof))
        model = self.mech.model
        for b in self.com:
            inertia = model.inertias[b]
            R = self.pdata.oMi[b].rotation
            block = scipy.linalg.block_diag(inertia.mass * np.eye(3), R @ inertia.inertia @ R.T)
            S = self.select(f"c{b}")
            M += S.T @ block @ S
        Z = scipy.linalg.null_space(self.C)
        mu = scipy.linalg.eigh(Z.T @ M @ Z, Z.T @ self.K @ Z, eigvals_only=True)[::-1]
        return 1.0 / np.sqrt(mu[:n]) / (2 * np.pi)
