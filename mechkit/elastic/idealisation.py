"""The idealisation: which bodies are beams, and the compliance every joint carries.

A body (a Pinocchio body: URDF links on fixed joints merged) with a section and one or two joints is
elastic: a massless straight beam from each joint's centre to its centre of mass, which carries the
body's mass and inertia. Bodies of three or more joints, the ground and bodies without a section are
rigid. Seen from the rigid mechanism, every joint then carries in series the cantilever compliance of
the beams that end at it (each clamped at its body's centre of mass) and its own compliance (a joint
stiffness on its constrained directions); an actuator carries its drive compliance (0: locked) and a
joint spring (`mechkit:spring`) the inverse of its stiffness.

Reactions follow the core's convention: joint order `ClosureModel.joint_names` (tree joints, then the
cuts), wrench [f, m] about the joint's origin (a cut: frame_b's origin), world axes.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin
import scipy.linalg

from mechkit import core
from mechkit.base.exceptions import InvalidParameters
from mechkit.elastic.beam import cantilever_compliance
from mechkit.elastic.sections import ElasticData, JointElasticity
from mechkit.mechanism import Mechanism

#: Beams shorter than this fraction of the mechanism's size count as rigid (a joint at the centre of mass).
SHORT_BEAM = 1e-9


@dataclass(frozen=True)
class ElasticBody:
    """An elastic body (a link idealised as beams).

    Attributes:
        body: Pinocchio joint id of the body.
        link: its URDF link carrying the section.
        joints: the joints (indices into `ClosureModel.joint_names`) it carries.
        lengths: (len(joints),) length (m) of the beam from each joint's centre to the centre of mass.
    """

    body: int
    link: str
    joints: tuple[int, ...]
    lengths: tuple[float, ...]


def _world_placements(model: pin.Model, q: np.ndarray) -> pin.Data:
    data = model.createData()
    pin.forwardKinematics(model, data, q)
    pin.updateFramePlacements(model, data)
    return data


class Idealisation:
    """The elastic idealisation of a mechanism (pose independent; evaluated at poses by `compliances`).

    Args:
        mech: the mechanism (`mechkit.Mechanism`).
        data: its elastic data (sections by URDF link, elasticity by joint).

    Attributes:
        elastic: the elastic bodies (`ElasticBody`).
        sides: (n_joints, 2) bodies of each joint's parent (frame_a) and child (frame_b) sides.
        drives: the effort columns beyond the actuators: joints with a `mechkit:spring` (not actuated).
        drive_compliance: (na + len(drives),) compliance of each effort column (rad/(N m) or m/N; 0: locked).
        size: the mechanism's size (m): the farthest joint origin from the world origin at home (1 mm at least).
        pin_data: a Pinocchio data (scratch of `mechkit.elastic.statics.evaluate`).
        pin_rotations: views of its joint placements' rotations.
        pin_translations: views of its joint placements' translations.

    Raises:
        InvalidParameters: a section or elasticity naming what the mechanism lacks, a section on a body the
            idealisation keeps rigid (three or more joints, or the ground: it would change nothing), a centre
            on a joint without an axis, a drive stiffness on a joint that is not actuated.
    """

    def __init__(self, mech: Mechanism, data: ElasticData):
        cm, model = mech.closure_model, mech.model
        self.mech, self.data = mech, data
        self.names = cm.joint_names
        self.pin_data = model.createData()
        placements = self.pin_data.oMi.tolist()  # their rotation and translation alias the data's memory
        self.pin_rotations = [M.rotation for M in placements]
        self.pin_translations = [M.translation for M in placements]
        home = _world_placements(model, mech.home_q)
        frames = model.frames
        sides, axes, origins = [], [], []
        for j in range(1, model.njoints):
            sides.append((model.parents[j], j))
            motion = np.array(home.joints[j].S).reshape(6, -1)
            axes.append(home.oMi[j].rotation @ motion[3:, 0] if motion.shape[1] == 1 and not motion[:3].any() else None)
            origins.append(home.oMi[j].translation.copy())
        for cut in cm.full_kernel.cuts:
            fa, fb = frames[cut.frame_a], frames[cut.frame_b]
            sides.append((fa.parentJoint, fb.parentJoint))
            c = cut.closure
            axes.append(home.oMf[cut.frame_a].rotation @ c.axis if c.kind == "revolute" else None)
            origins.append(home.oMf[cut.frame_b].translation.copy())
        self.sides = np.array(sides, dtype=int)
        index = {name: k for k, name in enumerate(self.names)}
        for name in data.joints:
            if name not in index:
                raise InvalidParameters("elastic joint", name, f"no such joint or cut; joints: {list(self.names)}")
        centres = [
            origins[k] + data.joints.get(name, JointElasticity()).centre * (axes[k] if axes[k] is not None else 0.0)
            for k, name in enumerate(self.names)
        ]
        for name, j in data.joints.items():
            if j.centre and axes[index[name]] is None:
                raise InvalidParameters(f"centre of {name}", j.centre, "a centre along the axis needs a revolute joint")
        scale = self.size = max(max((np.linalg.norm(o) for o in origins), default=1.0), 1e-3)

        # a point of the world at home, in a body's frame
        def local(body: int, point: np.ndarray) -> np.ndarray:
            return home.oMi[body].actInv(point) if body else point

        self._centre_body = self.sides[:, 1].copy()
        self._centre_local = np.array([local(int(b), c) for b, c in zip(self._centre_body, centres)]).reshape(-1, 3)
        body_links = {f.name: f for f in frames if f.type == pin.FrameType.BODY}
        count = np.bincount(self.sides.reshape(-1), minlength=model.njoints)
        self.elastic: list[ElasticBody] = []
        self._beam_blocks: list[tuple[int, int, np.ndarray]] = []  # (joint, body, (6, 6) compliance in the body frame)
        taken: dict[int, str] = {}
        for link, section in data.sections.items():
            if link not in body_links:
                raise InvalidParameters("section", link, f"no such link; links: {sorted(body_links)}")
            frame = body_links[link]
            body = frame.parentJoint
            if body in taken:
                raise InvalidParameters("section", link, f"its body already has the section of {taken[body]!r}")
            taken[body] = link
            if body == 0 or not 1 <= count[body] <= 2:
                beams = sorted(n for n, f in body_links.items() if f.parentJoint and 1 <= count[f.parentJoint] <= 2)
                why = "is the ground" if body == 0 else f"carries {count[body]} joints"
                raise InvalidParameters(
                    "section",
                    link,
                    f"its body {why}, and a body of three or more joints (or the ground) is rigid in the elastic "
                    f"idealisation: its section would change nothing. A beam is a body of one or two joints: give "
                    f"the section to one of {beams}, or split the body into links of at most two joints each",
                )
            axis1 = frame.placement.rotation @ section.axis1
            beam_section = (
                section
                if np.allclose(axis1, section.axis1)
                else type(section)(
                    section.E, section.G, section.A, section.I1, section.I2, section.J, axis1, section.density
                )
            )
            com = model.inertias[body].lever
            joints, lengths = [], []
            for k in np.flatnonzero((self.sides == body).any(axis=1)):
                centre = local(body, centres[k])
                length = float(np.linalg.norm(centre - com))
                joints.append(int(k)), lengths.append(length)
                if length > SHORT_BEAM * scale:
                    self._beam_blocks.append((int(k), body, cantilever_compliance(centre, com, beam_section)))
            self.elastic.append(ElasticBody(body, link, tuple(joints), tuple(lengths)))
        self._joint_blocks = self._joint_springs(mech, index, home)
        every = self._beam_blocks + self._joint_blocks
        incidence = np.zeros((len(self.names), len(every)))  # joint <- block
        incidence[[j for j, _, _ in every], np.arange(len(every))] = 1.0
        self._blocks = (
            None
            if not every
            else (np.array([b for _, b, _ in every], dtype=int), np.array([f for _, _, f in every]), incidence)
        )
        self.drives, self.drive_compliance = self._drives(mech, index)

    def _joint_springs(
        self, mech: Mechanism, index: dict[str, int], home: pin.Data
    ) -> list[tuple[int, int, np.ndarray]]:
        """(joint, body whose frame holds the block, (6, 6) compliance at the joint's centre) of every joint
        given a stiffness: W (W^T K W)^-1 W^T, W an orthonormal basis of its constrained directions."""
        out = []
        cm, model = mech.closure_model, mech.model
        nt = model.njoints - 1
        G, _, _ = core.kinematic_pass(cm, cm.create_data(), mech.home_q[None])
        rows = cm.full_kernel.row_wrenches(G)[0]
        for name, j in self.data.joints.items():
            if j.stiffness is None:
                continue
            k = index[name]
            if k < nt:
                body, frame_rotation = k + 1, np.eye(3)
                W = scipy.linalg.null_space(np.array(home.joints[k + 1].S).reshape(6, -1).T)
            else:
                cut = cm.full_kernel.cuts[k - nt]
                frame = model.frames[cut.frame_a]
                body, frame_rotation = frame.parentJoint, frame.placement.rotation
                w = rows[cm.full_kernel.cut_slices[k - nt]].copy()
                w[:, 3:] -= np.cross(home.oMf[cut.frame_b].translation, w[:, :3])
                Rb = home.oMi[body].rotation
                W = scipy.linalg.block_diag(Rb, Rb).T @ scipy.linalg.orth(w.T)
            F6 = scipy.linalg.block_diag(frame_rotation, frame_rotation)
            K = F6 @ np.diag(j.stiffness) @ F6.T
            out.append((k, body, W @ np.linalg.inv(W.T @ K @ W) @ W.T))
        return out

    def _drives(self, mech: Mechanism, index: dict[str, int]) -> tuple[tuple[str, ...], np.ndarray]:
        actuated = set(mech.actuated)
        for name, j in self.data.joints.items():
            if j.drive is not None and name not in actuated:
                raise InvalidParameters(
                    f"drive of {name}", j.drive, f"not an actuated joint; actuated: {sorted(actuated)}"
                )
        compliance = [
            1.0 / self.data.joints[a].drive if a in self.data.joints and self.data.joints[a].drive else 0.0
            for a in mech.actuated
        ]
        springs = [
            s
            for s in (mech.springs.springs if mech.springs else ())
            if s.stiffness > 0 and s.joint not in actuated and mech.model.nvs[mech.joint_id(s.joint)] == 1
        ]
        return tuple(s.joint for s in springs), np.array(compliance + [1.0 / s.stiffness for s in springs])

    def compliances(self, R: np.ndarray, t: np.ndarray, points: np.ndarray) -> np.ndarray:
        """Every joint's compliance for its reaction about its reporting point, at N poses.

        Args:
            R: (N, njoints, 3, 3) body rotations (world).
            t: (N, njoints, 3) body origins (world, m).
            points: (N, n_joints, 3) the reactions' points (joint origins, cut frame_b origins).

        Returns:
            (N, n_joints, 6, 6) compliances (m/N, rad/(N m)), world axes: the beams ending at each joint
            and its own compliance, in series.
        """
        n, nj = len(R), len(self.names)
        out = np.zeros((n, nj, 6, 6))
        if self._blocks is not None:
            bodies, F, incidence = self._blocks
            R6 = np.zeros((n, len(bodies), 6, 6))
            R6[..., :3, :3] = R6[..., 3:, 3:] = R[:, bodies]
            rotated = R6 @ F @ np.swapaxes(R6, -1, -2)  # (N, blocks, 6, 6) world axes
            out = (incidence @ rotated.reshape(n, len(bodies), 36)).reshape(n, nj, 6, 6)
        centre = (R[:, self._centre_body] @ self._centre_local[None, :, :, None])[..., 0] + t[:, self._centre_body]
        X = np.zeros((n, nj, 6, 6))  # reaction about the centre = X (reaction about the point)
        X[..., :3, :3] = X[..., 3:, 3:] = np.eye(3)
        d = points - centre
        X[..., 3, 1], X[..., 3, 2], X[..., 4, 2] = -d[..., 2], d[..., 1], -d[..., 0]  # m_c = m + d x f
        X[..., 4, 0], X[..., 5, 0], X[..., 5, 1] = d[..., 2], -d[..., 1], d[..., 0]
        return np.swapaxes(X, -1, -2) @ out @ X
