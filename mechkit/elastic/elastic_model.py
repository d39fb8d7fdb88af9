"""`ElasticModel`: a mechanism with its elastic idealisation, and one method per quantity.

Every quantity is linear about an assembled pose (small deformations, no geometric stiffness from
preload) and comes from the force method over the rigid mechanism (`mechkit.elastic.statics`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import pinocchio as pin

from mechkit.base import arguments
from mechkit.base.exceptions import InvalidArgument, InvalidParameters, MethodUnavailable
from mechkit.elastic import statics
from mechkit.elastic.body_stiffness import BodyStiffness, body_stiffness
from mechkit.elastic.idealisation import Idealisation
from mechkit.elastic.modes import Modes, modes
from mechkit.elastic.sections import ElasticData, JointElasticity, Section
from mechkit.elastic.urdf_elements import parse_elastic
from mechkit.mechanism import Mechanism


@dataclass(frozen=True)
class CompliantReactions:
    """Inverse dynamics of N samples with the reactions compatibility fixes.

    Attributes:
        joint_names: the reactions' joints (tree joints, then cuts).
        actuated: the drives (the actuators, then any other driven joint, locked).
        efforts: (N, n_drives) drive efforts (N m or N).
        reactions: (N, n_joints, 6) [f, m] about each joint's origin (a cut: frame_b's origin), world.
        determinate: (N, n_joints, 6) components fixed by equilibrium and compatibility (all, where every
            self-stress strains something elastic).
        rigid_determinate: (N, n_joints, 6) those rigid statics fixes alone: there the values equal the
            rigid inverse dynamics'.
        spring_efforts: (N, n_springs) increments of the joint springs treated as drives (N m or N).
    """

    joint_names: tuple[str, ...]
    actuated: tuple[str, ...]
    efforts: np.ndarray
    reactions: np.ndarray
    determinate: np.ndarray
    rigid_determinate: np.ndarray
    spring_efforts: np.ndarray

    def reaction(self, joint: str) -> np.ndarray:
        """The reactions of one joint.

        Args:
            joint: the joint's name (a tree joint or a cut).

        Returns:
            (N, 6) its reactions [f (N), m (N m)], world axes.

        Raises:
            InvalidParameters: no such joint.
        """
        if joint not in self.joint_names:
            raise InvalidParameters("joint", joint, f"no such joint; joints: {list(self.joint_names)}")
        return self.reactions[:, self.joint_names.index(joint)]


class ElasticModel:
    """A mechanism and its elastic idealisation (`mechkit.elastic.idealisation`).

    Args:
        mech: the mechanism (`mechkit.Mechanism`).
        data: its elastic data; default: the `<mechkit:beam>` and `<mechkit:elastic_joint>` elements of
            its URDF (none: every body rigid, and no quantity here can be computed).

    Raises:
        InvalidParameters: elastic data naming what the mechanism lacks, or that its joints cannot take.
        MalformedDescription: bad `<mechkit:beam>` or `<mechkit:elastic_joint>` elements in its URDF.
    """

    def __init__(self, mech: Mechanism, data: ElasticData | None = None):
        if data is None:
            urdf = mech.urdf if mech.urdf is not None else mech.source_urdf
            data = parse_elastic(urdf) if urdf is not None else ElasticData()
        self.mech, self.data = mech, data
        self.idealisation = Idealisation(mech, data)
        self.links = {f.name: f for f in mech.model.frames if f.type == pin.FrameType.BODY}
        self._structure: ElasticModel | None = None

    def structure(self) -> ElasticModel:
        """The same idealisation with every section of unit moduli, area and moments (its directions held
        rigidly are this model's: they depend on which elements yield, not on how much), made once.

        Returns:
            The `ElasticModel` of the structure.
        """
        if self._structure is None:
            unit = {link: Section(1.0, 1.0, 1.0, 1.0, 1.0, 1.0, s.axis1) for link, s in self.data.sections.items()}
            self._structure = ElasticModel(self.mech, ElasticData(unit, dict(self.data.joints)))
        return self._structure

    def require_elasticity(self) -> None:
        """Refuse, naming what is missing, a mechanism in which nothing yields (no beam, joint stiffness,
        drive stiffness or joint spring): every body rigid, no elastic quantity exists.

        Raises:
            MethodUnavailable: nothing elastic.
        """
        if not self.data and not self.idealisation.drives:
            raise MethodUnavailable(
                "the elastic model",
                f"{self.mech.spec.name} has no <mechkit:beam>, <mechkit:elastic_joint> or <mechkit:spring>: every "
                'body is rigid; give links sections (<mechkit:beam link="..." E= G= A= I1= I2= J= axis1=/>, '
                "docs/elastic.md) or pass an ElasticData",
            )

    def with_section(self, link: str, section: Section | None) -> ElasticModel:
        """The same mechanism with one link's section set.

        Args:
            link: the URDF link.
            section: its section (None: rigid).

        Returns:
            A new `ElasticModel`.

        Raises:
            InvalidParameters: no such link, or its body already has another link's section.
        """
        return ElasticModel(self.mech, self.data.with_section(link, section))

    def with_joint(self, joint: str, elasticity: JointElasticity | None) -> ElasticModel:
        """The same mechanism with one joint's elasticity set.

        Args:
            joint: the joint (a tree joint or a cut).
            elasticity: its elasticity (None: ideal, and locked when actuated).

        Returns:
            A new `ElasticModel`.

        Raises:
            InvalidParameters: no such joint, or elasticity the joint cannot take.
        """
        return ElasticModel(self.mech, self.data.with_joint(joint, elasticity))

    # ------------------------------------------------------------------ reactions
    def inverse_dynamics_batch(
        self, q: np.ndarray, v: np.ndarray, a: np.ndarray, fext: Any = None, *, allow_singular: bool = False
    ) -> CompliantReactions:
        """Efforts and reactions of N motions with every reaction fixed by equilibrium and compatibility.

        The rigid inverse dynamics moved along its self-stresses to the least complementary energy (loads
        act on each body's centre of mass node as in the rigid model).

        Args:
            q: (N, nq) configurations closing the loops.
            v: (N, nv) velocities.
            a: (N, nv) accelerations.
            fext: external forces as `Mechanism.inverse_dynamics_batch` takes them (None, (N, njoints, 6)
                or N per-sample values).
            allow_singular: skip the test that the inputs determine the motion.

        Returns:
            The `CompliantReactions` of the N samples.

        Raises:
            SingularConfiguration: the rigid efforts are undetermined (see `allow_singular`).
        """
        rigid = self.mech.inverse_dynamics_batch(q, v, a, fext, determinacy=False, allow_singular=allow_singular)
        return self.compatible(np.asarray(q, dtype=float).reshape(len(rigid), -1), rigid.efforts, rigid.reactions)

    def compatible(
        self, q: np.ndarray, efforts: np.ndarray, reactions: np.ndarray, drives: tuple[str, ...] | None = None
    ) -> CompliantReactions:
        """The compatible equilibrium nearest a rigid one, moved along the self-stresses.

        Args:
            q: (N, nq) poses closing the loops (e.g. a motion study's).
            efforts: (N, n_drives) the rigid equilibrium's drive efforts (N m or N).
            reactions: (N, n_joints, 6) its reactions [f, m], world axes, `ClosureModel.joint_names` order.
            drives: the joints the efforts drive, the actuators first (default: the actuators); a drive
                that is not an actuator is locked.

        Returns:
            The `CompliantReactions` of the N poses.

        Raises:
            InvalidParameters: drives that do not start with the actuators, or a pose that does not close
                the loops.
            InvalidArgument: arrays of the wrong shape or not finite.
        """
        mech = self.mech
        drives = tuple(mech.actuated) if drives is None else tuple(drives)
        if drives[: len(mech.actuated)] != tuple(mech.actuated):
            raise InvalidParameters("drives", drives, f"must start with the actuators {list(mech.actuated)}")
        (q,) = mech._many(q=q)
        n, nj = len(q), len(mech.closure_model.joint_names)
        for name, value, shape in (("efforts", efforts, (n, len(drives))), ("reactions", reactions, (n, nj, 6))):
            if np.shape(value) != shape:
                raise InvalidArgument(name, value, f"expected shape {shape}, got {np.shape(value)}")
        efforts = arguments.array("efforts", efforts, len(drives))
        reactions = arguments.array("reactions", np.reshape(reactions, (n, 6 * nj)), 6 * nj).reshape(n, nj, 6)
        actuation = mech.closure_model.with_actuation(drives).actuation
        ideal = self.idealisation
        na = len(mech.actuated)
        compliance = np.concatenate(
            [ideal.drive_compliance[:na], np.zeros(len(drives) - na), ideal.drive_compliance[na:]]
        )
        n = len(q)
        with np.errstate(under="ignore"):  # products of tiny compliances and lever arms flush to zero harmlessly
            pose = statics.evaluate(ideal, q, actuation)
            full = np.concatenate([efforts, np.zeros((n, len(ideal.drives)))], axis=1)
            out = statics.compatible(pose, compliance, reactions[..., None], full[..., None])
        return CompliantReactions(
            mech.closure_model.joint_names,
            drives,
            out.efforts[:, : len(drives), 0],
            out.reactions[..., 0],
            out.determinate,
            out.rigid_determinate,
            out.efforts[:, len(drives) :, 0],
        )

    def inverse_dynamics(
        self, q: np.ndarray, v: np.ndarray, a: np.ndarray, fext: Any = None, *, allow_singular: bool = False
    ) -> CompliantReactions:
        """`inverse_dynamics_batch` of one sample, as a batch of one.

        Args:
            q: (nq,) configuration closing the loops.
            v: (nv,) velocities.
            a: (nv,) accelerations.
            fext: external forces of the sample as `Mechanism.inverse_dynamics` takes them, or None.
            allow_singular: skip the test that the inputs determine the motion.

        Returns:
            The `CompliantReactions`, N = 1.
        """
        q, v, a = self.mech._one(q=q, v=v, a=a)
        return self.inverse_dynamics_batch(
            q[None], v[None], a[None], None if fext is None else [fext], allow_singular=allow_singular
        )

    # ------------------------------------------------------------------ stiffness
    def body(self, link: str) -> int:
        """The Pinocchio id of the body carrying a URDF link.

        Args:
            link: the URDF link.

        Returns:
            The body's joint id.

        Raises:
            InvalidParameters: no such link.
        """
        if link not in self.links:
            raise InvalidParameters("body", link, f"no such link; links: {sorted(self.links)}")
        return int(self.links[link].parentJoint)

    def point(self, q: np.ndarray, link: str, point: np.ndarray | None = None) -> np.ndarray:
        """A point given in a link's frame, in the world at a pose.

        Args:
            q: (nq,) configuration.
            link: the URDF link.
            point: (3,) the point in the link's frame (m); default its origin.

        Returns:
            (3,) the point in the world (m).
        """
        data = self.mech.model.createData()
        pin.framesForwardKinematics(self.mech.model, data, q)
        local = np.zeros(3) if point is None else arguments.array("point", point, 3, batch=False)
        return data.oMf[self.mech.model.getFrameId(link)].act(local)

    def compliance(self, q: np.ndarray, link: str, point: np.ndarray | None = None) -> np.ndarray:
        """The compliance C of a body at a point.

        Args:
            q: (nq,) an assembled pose.
            link: the body's URDF link.
            point: (3,) the point in the link's frame (m); default the link's origin.

        Returns:
            (6, 6) C: the body's twist [translation (m), rotation (rad)] per wrench [N, N m] at the
            point, world axes.

        Raises:
            InvalidParameters: no such link, or a pose that does not close the loops.
            SingularConfiguration: with its actuators locked the mechanism still moves under a load there.
        """
        return self._compliance(q, link, point)[0]

    def _compliance(self, q: np.ndarray, link: str, point: np.ndarray | None) -> tuple[np.ndarray, np.ndarray]:
        """C (6, 6) and the point (3,) in the world, from one kinematic pass."""
        (q,) = self.mech._one(q=q)
        body = self.body(link)
        local = np.zeros(3) if point is None else arguments.array("point", point, 3, batch=False)
        placement = self.links[link].placement
        with np.errstate(under="ignore"):
            pose = statics.evaluate(self.idealisation, q[None])
            x = pose.R[0, body] @ (placement.rotation @ local + placement.translation) + pose.t[0, body]
            return self._flexibility(pose, np.array([body]), x[None, None])[0], x

    def stiffness(self, q: np.ndarray, link: str, point: np.ndarray | None = None) -> BodyStiffness:
        """The stiffness of a body at a point (`mechkit.elastic.body_stiffness`: the directions held rigidly
        judged on the structure, the stiffness the inverse of the compliance off them).

        Args:
            q: (nq,) an assembled pose.
            link: the body's URDF link.
            point: (3,) the point in the link's frame (m); default its origin.

        Returns:
            The `BodyStiffness` (world axes at the point).

        Raises:
            InvalidParameters: no such link, or a pose that does not close the loops.
            MethodUnavailable: nothing in the mechanism is elastic (`require_elasticity`).
            SingularConfiguration: with its actuators locked the mechanism still moves under a load there.
        """
        self.require_elasticity()
        C, x = self._compliance(q, link, point)
        size = self.idealisation.size
        return body_stiffness(link, x, C, self.structure()._compliance(q, link, point)[0], min(size, size**3))

    def deflection(self, q: np.ndarray, link: str, wrench: np.ndarray, point: np.ndarray | None = None) -> np.ndarray:
        """A body's deflection at a point under a wrench there.

        Args:
            q: (nq,) an assembled pose.
            link: the body's URDF link.
            wrench: (6,) the wrench [N, N m] at the point, world axes.
            point: (3,) the point in the link's frame (m); default its origin.

        Returns:
            (6,) the twist [translation (m), rotation (rad)], world axes.
        """
        return self.compliance(q, link, point) @ arguments.array("wrench", wrench, 6, batch=False)

    def modes(self, q: np.ndarray, n: int = 6) -> Modes:
        """The first natural modes at a pose, actuators locked (`mechkit.elastic.modes`).

        Args:
            q: (nq,) an assembled pose.
            n: modes wanted (fewer come back where directions are held rigidly).

        Returns:
            The `Modes`, ascending in frequency.

        Raises:
            InvalidParameters: n < 1 or more than six per massive body.
            MethodUnavailable: nothing in the mechanism is elastic (`require_elasticity`).
            SingularConfiguration: the locked mechanism still moves (a zero frequency).
        """
        self.require_elasticity()
        (q,) = self.mech._one(q=q)
        model = self.mech.model
        bodies = np.array([j for j in range(1, model.njoints) if model.inertias[j].mass > 0], dtype=int)
        if not isinstance(n, (int, np.integer)) or n < 1 or n > 6 * len(bodies):
            raise InvalidParameters("n", n, f"between 1 and {6 * len(bodies)} (six per massive body)")
        with np.errstate(under="ignore"):
            pose = statics.evaluate(self.idealisation, q[None])
            centres = np.array([pose.R[0, b] @ model.inertias[int(b)].lever + pose.t[0, b] for b in bodies])
            F = self._flexibility(pose, bodies, centres[None])[0]
            structure = self.structure()
            rigid = structure._flexibility(statics.evaluate(structure.idealisation, q[None]), bodies, centres[None])[0]
            names = tuple(next(link for link, f in self.links.items() if f.parentJoint == b) for b in bodies)
            unit = min(self.idealisation.size, self.idealisation.size**3) * max(m.mass for m in model.inertias)
            return modes(model, pose.R[0], bodies, centres, F, n, names, rigid, unit)

    def _flexibility(self, pose: statics.Pose, bodies: np.ndarray, points: np.ndarray) -> np.ndarray:
        """(N, 6k, 6k) flexibility between unit wrenches at the bodies' points (N, k, 3)."""
        b, R0 = statics.unit_loads(self.mech.model, pose, bodies, points)
        x = statics.particular(pose, b)
        reactions = R0 + pose.reaction_map @ x[:, None]
        c = self.idealisation.drive_compliance
        out = statics.compatible(pose, c, reactions, x[:, : pose.efforts])
        C = statics.energy_product(pose, c, out.reactions, out.efforts, out.reactions, out.efforts)
        return (C + np.swapaxes(C, 1, 2)) / 2
