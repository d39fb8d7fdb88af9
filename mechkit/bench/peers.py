"""Peer simulators on the same mechanisms, for `mechkit bench`: MuJoCo and (optional) Drake.

Both are optional imports; a missing one raises `MethodUnavailable` with its install hint.

- MuJoCo (`pip install mechkit[peers]`): the MJCF of `mechkit.export.to_mjcf` (tree + `equality`
  connect/weld) without its springs and damping. Its equality constraints are soft: `solref`/`solimp`
  at MuJoCo's defaults (`DEFAULT_SOLREF`, `DEFAULT_SOLIMP`, not the export's), or "stiff"
  (`STIFF_SOLREF`, `STIFF_SOLIMP`: impedance at its cap, time constant 2 timesteps).
  Forward dynamics = `mj_forward` with the efforts as `qfrc_applied`, read `qacc`. Inverse
  dynamics = `mj_inverse` at the given acceleration, then the split of M a + c into actuator efforts
  and constraint forces on MuJoCo's own constraint Jacobian (least squares, as mechkit does on its
  rows); MuJoCo itself gives no such split.
- Drake (`pip install drake`): `MultibodyPlant` from the tree URDF, discrete (SAP) with time step
  `DRAKE_DT`, every point anchor as `AddBallConstraint`. It exposes no continuous acceleration: the
  forward dynamics is the one-step velocity change (v_next - v) / dt, which carries the implicit
  step's O(dt) error and SAP's regularisation. Its joint reactions (the reaction-forces port) are
  compared with ours in `mechkit.bench.reactions_engines`; it gives no inverse dynamics.

Coordinates: the same joint names and zero as mechkit (MuJoCo via `ref`, Drake via the URDF), so q,
v, a, tau are mechkit's vectors throughout.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from typing import TYPE_CHECKING

import numpy as np

from mechkit.base.exceptions import MechkitError, MethodUnavailable
from mechkit.bench.methods import Method
from mechkit.core import AXIS_ANCHOR_OFFSET
from mechkit.export import frame_b_vector, to_mjcf
from mechkit.mechanism import Mechanism
from mechkit.sources.urdf import LOOP_NAMESPACE

if TYPE_CHECKING:
    from pydrake.multibody.plant import MultibodyPlant

#: MuJoCo equality solref (time constant s, damping ratio) and solimp for the "stiff" setting.
STIFF_SOLREF = (0.002, 1.0)
STIFF_SOLIMP = (0.9999, 0.9999, 0.001, 0.5, 2.0)
#: MuJoCo's own defaults for equality constraints.
DEFAULT_SOLREF = (0.02, 1.0)
DEFAULT_SOLIMP = (0.9, 0.95, 0.001, 0.5, 2.0)
#: Drake's discrete time step (s).
DRAKE_DT = 1e-3


class SimulationFailed(MechkitError):
    """A peer simulator stopped with its own error (its message is kept)."""

    def __init__(self, peer: str, message: str):
        self.peer, self.message = peer, message
        super().__init__(f"{peer}: {message}")


def _import_mujoco():
    try:
        import mujoco
    except ImportError:
        raise MethodUnavailable("mujoco", "not installed: pip install 'mechkit[peers]'") from None
    return mujoco


class MujocoPeer:
    """MuJoCo model of a mechanism with mechkit's coordinates.

    Args:
        mech: the mechanism.
        stiff: use `STIFF_SOLREF` / `STIFF_SOLIMP` on every equality instead of MuJoCo's defaults.
    """

    def __init__(self, mech: Mechanism, stiff: bool = False):
        mujoco = self._mj = _import_mujoco()
        self.model = mujoco.MjModel.from_xml_string(to_mjcf(mech))
        self.model.eq_solref[:] = STIFF_SOLREF if stiff else DEFAULT_SOLREF
        self.model.eq_solimp[:] = STIFF_SOLIMP if stiff else DEFAULT_SOLIMP
        # mechkit's dynamics has no passive joint forces: drop the export's springs and dampers
        self.model.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_SPRING | mujoco.mjtDisableBit.mjDSBL_DAMPER
        self.data = mujoco.MjData(self.model)
        names = list(mech.model.names[1:])
        jid = [mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_JOINT, n) for n in names]
        self.qadr = np.array([self.model.jnt_qposadr[j] for j in jid])
        self.vadr = np.array([self.model.jnt_dofadr[j] for j in jid])
        self.actuated_v = np.array([mech.v_index(j) for j in mech.actuated])
        self.actuated = mech.actuated
        self.nv = self.model.nv

    def _efc_jacobian(self) -> np.ndarray:
        """MuJoCo's constraint Jacobian (nefc, nv) as a dense array (MuJoCo stores it sparse above nv = 60)."""
        d, nefc = self.data, self.data.nefc
        if not self._mj.mj_isSparse(self.model):
            return d.efc_J[: nefc * self.nv].reshape(nefc, self.nv)
        J = np.zeros((nefc, self.nv))
        for r in range(nefc):
            adr, nnz = d.efc_J_rowadr[r], d.efc_J_rownnz[r]
            J[r, d.efc_J_colind[adr : adr + nnz]] = d.efc_J[adr : adr + nnz]
        return J

    def set_state(
        self, q: np.ndarray, v: np.ndarray, tau: np.ndarray | None = None, a: np.ndarray | None = None
    ) -> None:
        """Write a state (mechkit order) into the MjData, for timing `mj_forward` / `mj_inverse` bare.

        Args:
            q: a configuration (nq,), mechkit's order.
            v: a velocity (nv,).
            tau: generalised efforts (nv,), N m or N, if any.
            a: accelerations (nv,), rad/s^2 or m/s^2, if any.
        """
        d = self.data
        d.qpos[self.qadr] = q
        d.qvel[self.vadr] = v
        if tau is not None:
            d.qfrc_applied[self.vadr] = tau
        if a is not None:
            d.qacc[self.vadr] = a

    def forward(self, q: np.ndarray, v: np.ndarray, tau: np.ndarray) -> np.ndarray:
        """Accelerations (mechkit order) under joint efforts tau.

        Args:
            q: a configuration (nq,), mechkit's order.
            v: a velocity (nv,).
            tau: generalised efforts (nv,), N m or N.

        Returns:
            MuJoCo's accelerations (nv,), mechkit's order, under its soft closure.
        """
        d = self.data
        self.set_state(q, v, tau)
        self._mj.mj_forward(self.model, d)
        return d.qacc[self.vadr].copy()

    def inverse(self, q: np.ndarray, v: np.ndarray, a: np.ndarray) -> dict[str, float]:
        """Actuator efforts holding the motion: M a + c = S u + J_eq^T f solved by least squares.

        Args:
            q: a configuration (nq,), mechkit's order.
            v: a velocity (nv,).
            a: accelerations (nv,).

        Returns:
            Actuated joint -> effort (N m or N).
        """
        d = self.data
        self.set_state(q, v, a=a)
        self._mj.mj_inverse(self.model, d)
        b = (d.qfrc_inverse + d.qfrc_constraint)[self.vadr]
        nefc = d.nefc
        J = self._efc_jacobian()[:, self.vadr]
        A = np.zeros((self.nv, len(self.actuated_v) + nefc))
        A[self.actuated_v, np.arange(len(self.actuated_v))] = 1.0
        A[:, len(self.actuated_v) :] = J.T
        x = np.linalg.lstsq(A, b, rcond=None)[0]
        return dict(zip(self.actuated, map(float, x[: len(self.actuated_v)])))


class DrakePeer:
    """Drake `MultibodyPlant` (discrete SAP) of a mechanism with ball constraints at the cuts.

    Raises:
        MethodUnavailable: Drake not installed, or a cut with no ball-constraint equivalent.
    """

    def __init__(self, mech: Mechanism, dt: float = DRAKE_DT):
        try:
            from pydrake.multibody.parsing import Parser
            from pydrake.multibody.plant import DiscreteContactApproximation, MultibodyPlant
            from pydrake.systems.analysis import Simulator
        except ImportError:
            raise MethodUnavailable("drake", "not installed: pip install drake") from None
        self.dt = dt
        plant = MultibodyPlant(time_step=dt)
        plant.set_discrete_contact_approximation(DiscreteContactApproximation.kSap)  # constraints need SAP
        Parser(plant).AddModelsFromString(_strip_loops(mech.urdf), "urdf")
        root = mech.model.frames[1].name  # the URDF root link
        if root != "world":  # a URDF root link called "world" is Drake's world body already
            plant.WeldFrames(plant.world_frame(), plant.GetFrameByName(root))
        add_armature(plant, mech)
        model, frames = mech.model, mech.model.frames
        for cut in mech.cuts:
            c = cut.closure
            if c.kind not in ("revolute", "spherical"):
                raise MethodUnavailable("drake", f"cut {c.name!r} is {c.kind}: only ball constraints are mapped")
            # rows "spherical" keep the alignment rows only (the cut at the linkage's fixed centre, where a
            # ball constraint's Jacobian is zero and SAP's Hessian turns NaN): the point along the axis alone
            offsets = [] if c.rows == "spherical" else [np.zeros(3)]
            if c.kind == "revolute" and c.rows != "planar":
                offsets.append(AXIS_ANCHOR_OFFSET * c.axis)
            fa, fb = frames[cut.frame_a], frames[cut.frame_b]
            for offset in offsets:
                body_a = _body_of(plant, model, fa.parentJoint)
                body_b = _body_of(plant, model, fb.parentJoint)
                p_a = fa.placement.act(offset)
                p_b = fb.placement.act(frame_b_vector(mech, cut, offset))
                plant.AddBallConstraint(body_a, p_a, body_b, p_b)
        plant.Finalize()
        self.plant = plant
        self.context = plant.CreateDefaultContext()
        names = list(model.names[1:])
        self.qadr = np.array([plant.GetJointByName(n).position_start() for n in names])
        self.vadr = np.array([plant.GetJointByName(n).velocity_start() for n in names])
        self.nq, self.nv = plant.num_positions(), plant.num_velocities()
        self._force = plant.get_applied_generalized_force_input_port().FixValue(self.context, np.zeros(self.nv))
        self._simulator = Simulator(plant, self.context)  # steps the plant's per-step discrete update
        self._simulator.Initialize()

    def forward(self, q: np.ndarray, v: np.ndarray, tau: np.ndarray) -> np.ndarray:
        """(v_next - v) / dt of one discrete step from (q, v) under efforts tau.

        Drake's own calls: the state written by `SetPositionsAndVelocities`, the efforts fixed on the
        applied-force port's fixed value, one `Simulator.AdvanceTo` (the clock runs on from call to call; the step
        does not depend on the time). Python glue is the two vector copies.

        Args:
            q: a configuration (nq,), mechkit's order.
            v: a velocity (nv,).
            tau: generalised efforts (nv,), N m or N.

        Returns:
            The mean accelerations of the step (nv,), mechkit's order.

        Raises:
            SimulationFailed: Drake stopped the step with its own error.
        """
        x = np.zeros(self.nq + self.nv)
        x[self.qadr] = q
        x[self.nq + self.vadr] = v
        f = np.zeros(self.nv)
        f[self.vadr] = tau
        self._force.GetMutableData().get_mutable_value().SetFromVector(f)
        self.plant.SetPositionsAndVelocities(self.context, x)
        try:
            self._simulator.AdvanceTo(self.context.get_time() + self.dt)
        except RuntimeError as err:
            raise SimulationFailed("drake", str(err).split(".")[0]) from None
        return (self.plant.GetVelocities(self.context)[self.vadr] - v) / self.dt


def _strip_loops(urdf: str) -> str:
    """The URDF without `<mechkit:loop>` elements (Drake's parser warns about unknown elements)."""
    root = ET.fromstring(urdf)
    for el in root.findall(f"{{{LOOP_NAMESPACE}}}loop"):
        root.remove(el)
    return ET.tostring(root, encoding="unicode")


def add_armature(plant: MultibodyPlant, mech: Mechanism) -> None:
    """Give Drake's joints mechkit's armature (the URDF has none) as actuators' rotor inertia, gear ratio 1.

    Args:
        plant: a `MultibodyPlant` parsed from `mech.urdf`, not finalised.
        mech: the mechanism.

    Raises:
        MethodUnavailable: armature on a joint of more than one degree of freedom.
    """
    model = mech.model
    for j in range(1, model.njoints):
        arm = model.armature[model.idx_vs[j] : model.idx_vs[j] + model.nvs[j]]
        if model.nvs[j] == 1 and arm[0] > 0:
            act = plant.AddJointActuator(f"{model.names[j]}__armature", plant.GetJointByName(model.names[j]))
            act.set_default_rotor_inertia(float(arm[0]))
            act.set_default_gear_ratio(1.0)
        elif np.any(arm > 0):
            raise MethodUnavailable("drake", f"joint {model.names[j]!r}: armature on a multi-dof joint is not mapped")


def _body_of(plant, model, joint: int):
    """Drake's body moved by mechkit's joint index (0: the root link)."""
    return plant.GetJointByName(model.names[joint]).child_body() if joint else plant.GetBodyByName(model.frames[1].name)


def peer_methods(mech: Mechanism) -> tuple[list[Method], list[str]]:
    """MuJoCo (default and stiff) and Drake rows; unavailable peers come back as notes.

    Args:
        mech: the mechanism.

    Returns:
        (the peers' methods, notes naming each peer that is unavailable and why).
    """
    methods, notes = [], []
    for stiff, label in ((False, "default"), (True, "stiff")):
        try:
            p = MujocoPeer(mech, stiff=stiff)
        except MechkitError as err:
            notes.append(f"MuJoCo {label}: {err}")
            continue
        methods.append(
            Method(
                f"MuJoCo mj_forward ({label} solref/solimp)",
                "forward_dynamics",
                lambda m, s, p=p: p.forward(s.q, s.v, s.tau),
                family="MuJoCo",
                peer=True,
                knob=label,
            )
        )
        if not stiff:
            methods.append(
                Method(
                    "MuJoCo mj_inverse + split on efc_J",
                    "inverse_dynamics",
                    lambda m, s, p=p: {"efforts": p.inverse(s.q, s.v, s.a)},
                    peer=True,
                )
            )
    try:
        d = DrakePeer(mech)
        methods.append(
            Method(
                f"Drake SAP step (dt={DRAKE_DT:g})",
                "forward_dynamics",
                lambda m, s, d=d: d.forward(s.q, s.v, s.tau),
                peer=True,
            )
        )
    except MechkitError as err:
        notes.append(f"Drake: {err}")
    return methods, notes
