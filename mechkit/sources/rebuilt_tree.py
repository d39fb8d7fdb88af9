"""A Pinocchio tree rebuilt with some of its joints changed: replaced by another joint model, split into
two revolutes, or locked (Gepetto's substitutions, `mechkit.sources.extended_urdf`; the joint types a URDF
parser does not know, `mechkit.sources.drake_joints`)."""

from __future__ import annotations

import pinocchio as pin

#: A revolute about its frame's X, Y or Z axis.
AXES = {"X": pin.JointModelRX, "Y": pin.JointModelRY, "Z": pin.JointModelRZ}


def rebuild(
    model: pin.Model, replace: dict[int, pin.JointModel], split: dict[int, tuple[str, str]], lock: list[int]
) -> pin.Model:
    """A copy of `model` with joints replaced (same placement, body and frames), joints split into two
    revolutes (`<name>_A` at the placement, `<name>_B` on it with the body and frames), then the joints
    `lock` (ids in `model`) locked at the zero configuration. Kept joints keep their limits.

    Args:
        model: the tree.
        replace: joint id -> the joint model put in its place.
        split: joint id -> (A, B), two of "X", "Y", "Z": the revolute axes, in the joint's frame.
        lock: joint ids locked at zero (their bodies merged into their parents).

    Returns:
        The new model.
    """
    new = pin.Model()
    new.name, new.gravity = model.name, model.gravity
    new.appendBodyToJoint(0, model.inertias[0], pin.SE3.Identity())  # the root link's inertia, as in the URDF model
    ids = {0: 0}
    for j in range(1, model.njoints):
        parent, place, name = ids[model.parents[j]], model.jointPlacements[j], model.names[j]
        if j in split:
            first, second = split[j]
            parent = new.addJoint(parent, AXES[first](), place, f"{name}_{first}")
            added = new.addJoint(parent, AXES[second](), pin.SE3.Identity(), f"{name}_{second}")
        elif j in replace:
            added = new.addJoint(parent, replace[j], place, name)
        else:
            jm = model.joints[j]
            q, v = slice(jm.idx_q, jm.idx_q + jm.nq), slice(jm.idx_v, jm.idx_v + jm.nv)
            added = new.addJoint(
                parent,
                jm,
                place,
                name,
                model.lowerEffortLimit[v],
                model.upperEffortLimit[v],
                model.lowerVelocityLimit[v],
                model.upperVelocityLimit[v],
                model.lowerPositionLimit[q],
                model.upperPositionLimit[q],
                model.lowerDryFrictionLimit[v],
                model.upperDryFrictionLimit[v],
                model.damping[v],
            )
        new.appendBodyToJoint(added, model.inertias[j], pin.SE3.Identity())
        ids[j] = added
    frames, parents = {0: 0}, []
    for f, frame in enumerate(model.frames):
        if f == 0:
            continue
        if (
            frame.type == pin.FrameType.JOINT
            and frame.parentJoint in split
            and frame.name == model.names[frame.parentJoint]
        ):
            for axis in split[frame.parentJoint]:  # the joint's frame becomes the two revolutes' frames
                sub = f"{frame.name}_{axis}"
                frames[f] = new.addFrame(
                    pin.Frame(sub, new.getJointId(sub), pin.SE3.Identity(), pin.FrameType.JOINT), False
                )
                parents.append((frames[f], frame.parentFrame))
            continue
        frames[f] = new.addFrame(
            pin.Frame(frame.name, ids[frame.parentJoint], frame.placement, frame.type, frame.inertia), False
        )
        parents.append((frames[f], frame.parentFrame))
    for f, parent in parents:  # a reduced model's frames may name a parent frame listed after them
        new.frames[f].parentFrame = frames[parent]
    return pin.buildReducedModel(new, [ids[j] for j in lock], pin.neutral(new)) if lock else new
