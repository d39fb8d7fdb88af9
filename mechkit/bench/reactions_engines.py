"""Tree-joint reactions of mechkit (rigid) beside Drake's and MuJoCo's, in one convention.

The convention (mechkit's): the wrench [f (N), m (N m)] the parent side of a joint exerts on its child
side, world axes, moment about the joint origin. Conversions:

- Drake's reaction-forces port gives F_CJc_Jc: the spatial force on the child body at the joint's
  child frame Jc, expressed in Jc (not world). A URDF joint's Jc origin is the joint origin, so the
  point stays; both vectors are rotated to world by R_WJc and reordered ([m, f] -> [f, m]).
- MuJoCo's `cfrc_int` (after `mj_rnePostConstraint`) is [m, f] on a body from its parent, world axes,
  moment about the subtree centre of mass c of the body's root: m_p = m_c + (c - p) x f moves it to
  the joint origin p.

Three engines' answers: `drake_tree` is Drake's continuous plant of the open tree under mechkit's cut
wrenches as external forces (an independent Newton-Euler of the same loads: agreement to round-off);
`drake_sap` is Drake's own closed model (discrete SAP, ball constraints at the cuts, `peers.DrakePeer`):
its reactions of one step from the state; `mujoco` its soft closure (default solref/solimp) at the
state. Closure error: |J (a - a_rigid)| (the acceleration-level closure residual J a + J'v of the
engine's accelerations, since J a_rigid = -J'v).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import MethodUnavailable
from mechkit.bench.peers import DrakePeer, MujocoPeer, _body_of, _strip_loops, add_armature
from mechkit.mechanism import Mechanism


def rigid(mech: Mechanism, q: np.ndarray, v: np.ndarray, tau: np.ndarray) -> dict:
    """mechkit's accelerations and reactions under joint efforts.

    Args:
        mech: the mechanism.
        q: (nq,) an assembled configuration.
        v: (nv,) velocities with J v = 0.
        tau: (nv,) generalised efforts (N m or N) on the actuated joints.

    Returns:
        {"a": (nv,), "reactions": (n_joints, 6) tree joints then cuts, "determinate": (n_joints, 6) bool}.
    """
    a = mech.forward_dynamics(q, v, tau, "kkt").a
    r = mech.inverse_dynamics(q, v, a, determinacy=True, allow_singular=True)
    det = np.array([r.reactions[n].determinate for n in r.joint_names])
    support = np.array([r.reactions[n].support for n in r.joint_names])
    return {"a": a, "reactions": np.asarray(r.reaction_values), "determinate": det, "support": support}


def resultant(mech: Mechanism, q: np.ndarray, reactions: np.ndarray, support: np.ndarray) -> np.ndarray:
    """What the ground's joints exert in total: [f, m about the world origin], world axes.

    Statics fixes it even where single components are indeterminate.

    Args:
        mech: the mechanism.
        q: (nq,) configuration.
        reactions: (njoints - 1, 6) tree-joint reactions, mechkit's convention.
        support: (njoints - 1,) True for a joint whose parent side is the ground.

    Returns:
        (6,) the sum of the support reactions moved to the world origin.
    """
    _, points = _joint_points(mech, q)
    f, m = reactions[support, :3], reactions[support, 3:]
    return np.r_[f.sum(axis=0), (m + np.cross(points[support], f)).sum(axis=0)]


def _joint_points(mech: Mechanism, q: np.ndarray) -> tuple[pin.Data, np.ndarray]:
    data = mech.model.createData()
    pin.framesForwardKinematics(mech.model, data, q)
    return data, np.array([data.oMi[j].translation for j in range(1, mech.model.njoints)])


def drake_tree(mech: Mechanism, q: np.ndarray, v: np.ndarray, tau: np.ndarray, cut_wrenches: np.ndarray) -> dict:
    """Drake's continuous open tree under the efforts and mechkit's cut wrenches as external forces.

    Args:
        mech: the mechanism.
        q: (nq,) configuration.
        v: (nv,) velocities.
        tau: (nv,) generalised efforts (N m or N).
        cut_wrenches: (ncuts, 6) each cut's [f, m about frame_b's origin], world, on frame_b's body.

    Returns:
        {"a": (nv,) Drake's accelerations, "reactions": (njoints - 1, 6) mechkit's convention}.

    Raises:
        MethodUnavailable: Drake not installed.
    """
    try:
        from pydrake.multibody.math import SpatialForce
        from pydrake.multibody.parsing import Parser
        from pydrake.multibody.plant import ExternallyAppliedSpatialForce, MultibodyPlant
    except ImportError:
        raise MethodUnavailable("drake", "not installed: pip install drake") from None
    plant = MultibodyPlant(time_step=0.0)
    Parser(plant).AddModelsFromString(_without_limits(_strip_loops(mech.urdf)), "urdf")
    model, frames = mech.model, mech.model.frames
    if frames[1].name != "world":
        plant.WeldFrames(plant.world_frame(), plant.GetFrameByName(frames[1].name))
    add_armature(plant, mech)
    plant.Finalize()
    ctx = plant.CreateDefaultContext()
    names = list(model.names[1:])
    joints = [plant.GetJointByName(n) for n in names]
    x = np.zeros(plant.num_positions() + plant.num_velocities())
    for j, qi, vi in zip(joints, q, v):
        x[j.position_start()], x[plant.num_positions() + j.velocity_start()] = qi, vi
    plant.SetPositionsAndVelocities(ctx, x)
    f = np.zeros(plant.num_velocities())
    for j, ti in zip(joints, tau):
        f[j.velocity_start()] = ti
    plant.get_applied_generalized_force_input_port().FixValue(ctx, f)
    data, _ = _joint_points(mech, q)
    forces = []
    for cut, w in zip(mech.cuts, cut_wrenches):
        fa, fb = frames[cut.frame_a], frames[cut.frame_b]
        p_w = data.oMf[cut.frame_b].translation
        for frame, sign in ((fa, -1.0), (fb, 1.0)):
            e = ExternallyAppliedSpatialForce()
            body = _body_of(plant, model, frame.parentJoint)
            e.body_index = body.index()
            e.p_BoBq_B = body.EvalPoseInWorld(ctx).inverse().multiply(p_w)
            e.F_Bq_W = SpatialForce(sign * w[3:], sign * w[:3])
            forces.append(e)
    plant.get_applied_spatial_force_input_port().FixValue(ctx, forces)
    a_all = plant.get_generalized_acceleration_output_port().Eval(ctx)
    return {"a": np.array([a_all[j.velocity_start()] for j in joints]), "reactions": _in_world(plant, ctx, joints)}


def _without_limits(urdf: str) -> str:
    """The URDF without joint limits (a continuous plant ignores them, and warns on every build)."""
    root = ET.fromstring(urdf)
    for joint in root.iter("joint"):
        for limit in joint.findall("limit"):
            joint.remove(limit)
    return ET.tostring(root, encoding="unicode")


def _in_world(plant, ctx, joints) -> np.ndarray:
    """Drake's F_CJc_Jc of the joints as (n, 6) [f, m about Jc's origin], world axes."""
    rf = plant.get_reaction_forces_output_port().Eval(ctx)
    out = []
    for j in joints:
        R = j.frame_on_child().CalcRotationMatrixInWorld(ctx).matrix()
        F = rf[int(j.index())]
        out.append(np.r_[R @ F.translational(), R @ F.rotational()])
    return np.array(out)


def drake_sap(mech: Mechanism, q: np.ndarray, v: np.ndarray, tau: np.ndarray) -> dict:
    """Drake's closed model (discrete SAP, ball constraints at the cuts): one step from the state.

    Args:
        mech: the mechanism.
        q: (nq,) configuration.
        v: (nv,) velocities.
        tau: (nv,) generalised efforts (N m or N).

    Returns:
        {"a": (nv,) (v_next - v) / dt, "reactions": (njoints - 1, 6) of that step, mechkit's convention}.

    Raises:
        MethodUnavailable: Drake not installed, or a cut it cannot close.
    """
    peer = DrakePeer(mech)
    a = peer.forward(q, v, tau)  # sampled output ports then hold this step's reactions
    joints = [peer.plant.GetJointByName(n) for n in mech.model.names[1:]]
    return {"a": a, "reactions": _in_world(peer.plant, peer.context, joints)}


def mujoco(mech: Mechanism, q: np.ndarray, v: np.ndarray, tau: np.ndarray) -> dict:
    """MuJoCo's soft closure (default solref/solimp) at the state: `cfrc_int` moved to the joint origins.

    Args:
        mech: the mechanism.
        q: (nq,) configuration.
        v: (nv,) velocities.
        tau: (nv,) generalised efforts (N m or N).

    Returns:
        {"a": (nv,), "reactions": (njoints - 1, 6) mechkit's convention, "equality": the equality rows'
        efc_force (N or N m)}.

    Raises:
        MethodUnavailable: MuJoCo not installed.
    """
    peer = MujocoPeer(mech)
    a = peer.forward(q, v, tau)
    mj, m, d = peer._mj, peer.model, peer.data
    mj.mj_rnePostConstraint(m, d)
    _, points = _joint_points(mech, q)
    out = []
    for name, p in zip(mech.model.names[1:], points):
        b = m.jnt_bodyid[mj.mj_name2id(m, mj.mjtObj.mjOBJ_JOINT, name)]
        mom, f = d.cfrc_int[b, :3], d.cfrc_int[b, 3:]
        c = d.subtree_com[m.body_rootid[b]]
        out.append(np.r_[f, mom + np.cross(c - p, f)])
    eq = d.efc_force[: d.nefc][d.efc_type[: d.nefc] == mj.mjtConstraint.mjCNSTR_EQUALITY].copy()
    return {"a": a, "reactions": np.array(out), "equality": eq}


def compare(mech: Mechanism, q: np.ndarray, v: np.ndarray, tau: np.ndarray) -> dict:
    """Every engine's tree-joint reactions and closure error beside mechkit's.

    The description's joint springs act in mechkit's dynamics; the engines' models have none, so they get
    the springs' torques added to tau.

    Args:
        mech: the mechanism.
        q: (nq,) an assembled configuration.
        v: (nv,) velocities with J v = 0.
        tau: (nv,) generalised efforts (N m or N) on the actuated joints.

    Returns:
        {"rigid": `rigid`'s dict, "joints": tree joint names, engine name -> its dict plus "closure"
        (|J (a - a_rigid)|, m/s^2 or rad/s^2), "diff" ((n_tree, 6) engine - rigid) and "resultant" (`resultant`,
        also in "rigid"); engines that are
        unavailable -> their reason (str)}.
    """
    ours = rigid(mech, q, v, tau)
    ntree = mech.model.njoints - 1
    ours["resultant"] = resultant(mech, q, ours["reactions"][:ntree], ours["support"][:ntree])
    out = {"rigid": ours, "joints": list(mech.model.names[1:])}
    J = mech.closure_jacobian(q)
    passive = mech.passive_forces(q, v)  # the description's joint springs: ours act, the peers' models have none
    total = tau if passive is None else tau + passive
    runs = {
        "drake_tree": lambda: drake_tree(mech, q, v, total, ours["reactions"][ntree:]),
        "drake_sap": lambda: drake_sap(mech, q, v, total),
        "mujoco": lambda: mujoco(mech, q, v, total),
    }
    for name, run in runs.items():
        try:
            r = run()
        except MethodUnavailable as err:
            out[name] = str(err)
            continue
        r["closure"] = float(np.max(np.abs(J @ (r["a"] - ours["a"]))))
        r["diff"] = r["reactions"] - ours["reactions"][:ntree]
        r["resultant"] = resultant(mech, q, r["reactions"], ours["support"][:ntree])
        out[name] = r
    return out
