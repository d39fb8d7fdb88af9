"""Only the part of a mechanism a study needs: joints locked at values, one subsystem kept, a floating
root fixed.

A locked joint is welded at its value (`pin.buildReducedModel`): its child body moves with its parent,
mass included, so the rest of the mechanism feels its weight exactly as before. `keep` locks every
joint outside the subsystem the kept bodies form (the joints carrying them, and every joint on a loop
through them) at the home configuration: the dropped part's weight stays on the bodies it hangs from,
a wrench on them, and a study of one leg of a robot with a fixed pelvis gets that leg's efforts exactly.
`fix` locks a body's own joint (a floating root: a free-flyer) at home. Loops whose joints are all
locked close at the locked values (else the reduction is refused with the residual); couplings between
locked joints drop, and one touching a locked joint is refused; springs and motors on locked joints
drop.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence

import numpy as np
import pinocchio as pin

from mechkit import core
from mechkit.base import joint_arguments
from mechkit.base.exceptions import InvalidArgument, MalformedDescription
from mechkit.mechanism import Mechanism
from mechkit.sources import Description

#: Largest closure residual (m, or dimensionless for alignment rows) of a loop the locked joints close.
LOCKED_LOOP_TOL = 1e-9


def locked_joints(
    mech: Mechanism,
    lock: Mapping[str, float | Sequence[float]] | None = None,
    keep: Sequence[str] | None = None,
    fix: Sequence[str] | None = None,
) -> dict[str, np.ndarray]:
    """The joints to lock and their configurations (their coordinates in q), from the three requests.

    Args:
        mech: the whole mechanism (its home assembly is the reference configuration).
        lock: joint -> value (rad or m; a ball's rotation vector, a free-flyer's position and rotation vector).
        keep: bodies (Pinocchio body frames, e.g. URDF links) whose subsystem stays free.
        fix: bodies whose own joint is locked at home (a floating root).

    Returns:
        joint name -> its q coordinates (nq_j,) at the locked configuration.

    Raises:
        InvalidArgument: an unknown joint or body, a malformed value, a body on the ground.
    """
    model, q = mech.model, mech.home_q.copy()
    names = list(model.names[1:])
    out: dict[str, np.ndarray] = {}
    if lock:
        values = joint_arguments.joint_values("lock", lock, list(lock), names)
        for joint, value in values.items():
            j = model.getJointId(joint)
            core.set_joint_value(model, q, j, value)
            out[joint] = q[model.idx_qs[j] : model.idx_qs[j] + model.nqs[j]].copy()
    if keep is not None:
        if isinstance(keep, str) or not keep:
            raise InvalidArgument("keep", keep, "expected a non-empty sequence of body names")
        kept = {_body_joint(model, body, "keep") for body in keep}
        moving = set(kept)
        for lp in mech.structure.loops:
            on_loop = {model.getJointId(j) for j in lp.joints}
            if on_loop & kept:
                moving |= on_loop
        for j in range(1, model.njoints):
            if j not in moving and model.names[j] not in out:
                out[model.names[j]] = q[model.idx_qs[j] : model.idx_qs[j] + model.nqs[j]].copy()
    for body in fix or ():
        j = _body_joint(model, body, "fix")
        out[model.names[j]] = q[model.idx_qs[j] : model.idx_qs[j] + model.nqs[j]].copy()
    return out


def _bodies(model: pin.Model) -> list[str]:
    return [f.name for f in model.frames if f.type == pin.FrameType.BODY]


def _body_joint(model: pin.Model, body: str, arg: str) -> int:
    if not model.existFrame(body, pin.FrameType.BODY):
        raise InvalidArgument(arg, body, f"not a body; bodies: {_bodies(model)}")
    j = model.frames[model.getFrameId(body, pin.FrameType.BODY)].parentJoint
    if j == 0:
        raise InvalidArgument(arg, body, "is the ground: it does not move")
    return j


def description_of(mech: Mechanism) -> Description:
    """What a file reader would give for the mechanism: its tree, closures, couplings, springs, actuators,
    home inputs and guess.

    Args:
        mech: a loaded mechanism.

    Returns:
        Its `Description`.
    """
    spec, params = mech.spec, mech.params
    return Description(
        spec.name,
        mech.urdf,
        tuple(mech.actuated),
        dict(spec.home(params)),
        dict(spec.guess(params)) if spec.guess is not None else {},
        model=mech.model,
        source_urdf=mech.source_urdf,
        closures=tuple(mech.closures),
        couplings=mech.closure_model.couplings,
        springs=mech.springs.springs,
        actuators=mech.closure_model.actuators,
        pose=mech.spec.pose or ("the spec's guess" if spec.guess is not None else "the joints' zero"),
        format="mechkit",
    )


def reduce_description(mech: Mechanism, desc: Description, locked: Mapping[str, np.ndarray]) -> Description:
    """The description with the `locked` joints welded at their coordinates (`locked_joints`).

    Args:
        mech: the mechanism the description is of.
        desc: its description (`description_of`, or a reader's).
        locked: joint name -> its coordinates (nq of the joint,), rad or m.

    Returns:
        The reduced description (the same one when nothing is locked).

    Raises:
        MalformedDescription: a loop the locked joints leave open (its residual), a coupling touching
            a locked joint and a free one.
    """
    model = mech.model
    if not locked:
        return desc
    q = mech.home_q.copy()
    for joint, coordinates in locked.items():
        j = model.getJointId(joint)
        q[model.idx_qs[j] : model.idx_qs[j] + model.nqs[j]] = coordinates
    reduced = _reduced_model(model, [model.getJointId(j) for j in locked], q)
    closures = []
    for closure in mech.closures:
        fa, fb = (reduced.frames[reduced.getFrameId(f)] for f in (closure.frame_a, closure.frame_b))
        if fa.parentJoint != fb.parentJoint:
            closures.append(closure)
            continue
        residual = _locked_loop_residual(mech, closure, q)
        if residual > LOCKED_LOOP_TOL:
            raise MalformedDescription(
                f"loop {closure.name!r}",
                f"every joint of it is locked and the locked values leave it open by {residual:.3e}",
            )
    couplings = []
    for coupling in desc.couplings:
        joints = [j for j, _ in coupling.follower + coupling.leader]
        if any(j in locked for j in joints):
            if not all(j in locked for j in joints):
                raise MalformedDescription(
                    f"coupling {coupling.name!r}",
                    f"couples a locked joint with a free one: lock all of {joints} or none",
                )
            continue
        couplings.append(coupling)
    actuators = tuple(
        dataclasses.replace(a, joints=tuple((j, c) for j, c in a.joints if j not in locked)) for a in desc.actuators
    )
    actuators = tuple(a for a in actuators if a.joints)
    names = {a.name for a in actuators}
    actuated = tuple(a for a in desc.actuated if a not in locked and (reduced.existJointName(a) or a in names))
    free = {k: v for k, v in desc.home.items() if k not in locked and reduced.existJointName(k)}
    guess = {k: v for k, v in desc.guess.items() if k not in locked and reduced.existJointName(k)}
    return dataclasses.replace(
        desc,
        name=f"{desc.name} (reduced)",
        urdf=None,
        source_urdf=desc.urdf if desc.urdf is not None else desc.source_urdf,
        model=reduced,
        closures=tuple(closures),
        couplings=tuple(couplings),
        springs=tuple(s for s in desc.springs if s.joint not in locked),
        actuators=actuators,
        actuated=actuated,
        home=free,
        guess=guess,
    )


def _reduced_model(model: pin.Model, joints: list[int], q: np.ndarray) -> pin.Model:
    """`pin.buildReducedModel`, with frames that share a name (a joint's and a body's, as readers write
    them) told apart while it runs (it looks frames up by name) and named back after."""
    work = model.copy()
    seen: dict[str, int] = {}
    renamed: dict[str, str] = {}
    for i, frame in enumerate(work.frames):
        seen[frame.name] = seen.get(frame.name, 0) + 1
        if seen[frame.name] > 1:
            unique = f"{frame.name}#mechkit{i}"
            renamed[unique] = frame.name
            frame.name = unique
            work.frames[i] = frame
    reduced = pin.buildReducedModel(work, joints, q)
    for i, frame in enumerate(reduced.frames):
        if frame.name in renamed:
            frame.name = renamed[frame.name]
            reduced.frames[i] = frame
    return reduced


def _locked_loop_residual(mech: Mechanism, closure: core.LoopClosure, q: np.ndarray) -> float:
    """The residual norm of one closure's rows at q (every joint of its loop locked)."""
    rows = core.ClosureModel(mech.model, [closure])
    return float(np.linalg.norm(core.closure_residual(rows, rows.create_data(), q)))
