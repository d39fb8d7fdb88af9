"""Extended URDF (Batto, de Matteis, Mansard; Gepetto's example-parallel-robots), read the way Gepetto's
loader reads it (`loader_tools.completeRobotLoader`, then `simplifyModel`): a tree URDF plus a YAML
sidecar beside it,

    closed_loop: [[frame_a, frame_b], ...]   # Pinocchio frames of any kind: links, joints, fixed joints
    type: ['3d' | '6d', ...]                 # 3d: the origins coincide (spherical cut); 6d: the frames do (weld)
    name_mot: [joint, ...]                   # the motors
    joint_name: [joint, ...]                 # optional substitutions, applied to the URDF's tree:
    joint_type: ['SPHERICAL' | 'FIXED' | 'UJOINT_AB', ...]

SPHERICAL puts a ball joint at the joint's placement; FIXED locks the joint at zero, its body merged
into its parent; UJOINT_AB (A, B in X, Y, Z) is a revolute about the joint frame's A axis named
`<joint>_A` then one about its B axis named `<joint>_B`, which carries the body and the joint's frames.
Then, as Gepetto's `simplifyModel` does, every chain of three revolutes about their own X/Y/Z axes
(consecutive joints, each the parent of the next) whose first two weigh under 1e-5 kg, whose axes are
pairwise not collinear (|a x b| > 1e-6) and whose origins lie within 1e-4 m at the zero configuration
becomes one ball joint at the third: the first two are locked at zero (`balls=False` keeps the three
revolutes: the same mechanism, parametrised by three angles). `freeflyer=True` puts the tree on a
free-flyer root named "root_joint", held at the URDF's origin in the home assembly (a home input at
position and rotation zero), so that fixing it gives the fixed-base robot's home. The model is built
directly (`Description.model`): a ball joint has no URDF. Only where it is the URDF's own tree (no
substitution, no ball, fixed base) does the description also carry the URDF text, with the pairs as
`<mechkit:loop>` elements.

Where Gepetto's loader is silent mechkit refuses by name: a substitution naming a joint the URDF lacks
(it keeps the joint as it is: a different mechanism than the file means), an unknown joint_type (it
reuses the previous joint's model), a motor it cannot find (it drops it), a frame on no body pair.
Where it would pick the wrong joint mechkit does not follow it: a triplet must be a chain (not only
three consecutive ids), and FIXED locks the named joint (it locks by the joint's id in the URDF model,
which a UJOINT before it shifts).

Two 3d pairs joining the same two bodies at distinct points are one revolute cut about the line
through them (the way `mechkit export` writes a hinge): its frames are the first pair's, its axis the
direction to the second pair, in frame_a's frame.
"""

from __future__ import annotations

import dataclasses
import difflib
import re
from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import MalformedDescription
from mechkit.core import LoopClosure
from mechkit.sources.description import Description, read_text
from mechkit.sources.rebuilt_tree import rebuild
from mechkit.sources.urdf import LOOP_NAMESPACE, build_model, describe_urdf

SUBSTITUTIONS = ("SPHERICAL", "FIXED", "UJOINT_AB (A, B two of X, Y, Z)")
#: The free-flyer root joint's name (`freeflyer=True`), as Pinocchio's URDF parser names it.
ROOT = "root_joint"
_UJOINT = re.compile(r"UJOINT_([XYZ])([XYZ])")
_REVOLUTES = {"JointModelRX": 0, "JointModelRY": 1, "JointModelRZ": 2}


@dataclasses.dataclass(frozen=True)
class Sidecar:
    """A checked sidecar: frame pairs and their kinds ("3d" | "6d"), motors (None: not given), substitutions."""

    pairs: list[tuple[str, str]]
    kinds: list[str]
    motors: tuple[str, ...] | None
    substitutions: dict[str, str]


def sidecar_of(path: Path) -> Path | None:
    """The sidecar of a URDF: the `.yaml` (or `.yml`) of the same stem, else `robot.yaml` in the same
    folder when that URDF is the folder's only one (Gepetto's loader reads `robot.yaml` by default).

    Args:
        path: a URDF file.

    Returns:
        The sidecar, or None.
    """
    for candidate in (path.with_suffix(".yaml"), path.with_suffix(".yml")):
        if candidate.is_file():
            return candidate
    default = path.parent / "robot.yaml"
    if default.is_file() and [p.name for p in path.parent.glob("*.urdf")] == [path.name]:
        return default
    return None


def read_extended_urdf(path: Path, sidecar: Path, freeflyer: bool = False, balls: bool = True) -> Description:
    """The mechanism of a URDF and its sidecar, built as Gepetto's loader builds it (see the module).

    Args:
        path: the tree URDF.
        sidecar: its YAML sidecar (`closed_loop`, `type`, `name_mot`).
        freeflyer: put the tree on a free-flyer root joint ("root_joint") instead of the world; its home
            value is the URDF's origin.
        balls: merge the spherical triplets into ball joints, as Gepetto's `simplifyModel` does.

    Returns:
        The description: `model` the Pinocchio model (any joint), `closures` the pairs as cuts,
        `actuated` the motors (else the URDF's transmissions), `urdf` the URDF with its loops only
        where the model is the URDF's own tree, else None.

    Raises:
        MalformedDescription: a malformed URDF or sidecar, a substitution, motor or frame that names
            nothing in the model, a pair on one body (naming the element and the reason).
    """
    urdf = read_text(path)
    side = _read_sidecar(sidecar)
    base = describe_urdf(urdf, path, "extended-urdf")  # the tree, its inertias, its own loops, home, mimics
    tree = build_model(urdf, pin.JointModelFreeFlyer() if freeflyer else None)
    model = _substitute(tree, side.substitutions, f"{sidecar}: joint_name", path.name)
    model, triplets = _spherical_triplets(model) if balls else (model, [])
    motors = side.motors if side.motors is not None else base.actuated
    for motor in motors:
        _one_freedom(model, motor, f"{sidecar}: name_mot", path.name)
    for coupling in base.couplings:
        for joint, _ in coupling.follower + coupling.leader:
            _one_freedom(model, joint, f"joint {coupling.name!r} <mimic>", path.name)
    for joint in base.home:
        _one_freedom(model, joint, f"mechkit:home {joint!r}", path.name)
    closures = _closures(model, side, sidecar, path.name)
    if freeflyer or side.substitutions or triplets:
        own = tuple(_checked_frames(model, c, path.name) for c in base.closures or ())
        home = {**base.home, ROOT: (0.0,) * 6} if freeflyer else base.home  # the root held where the URDF puts it
        return dataclasses.replace(
            base, urdf=None, actuated=tuple(motors), closures=own + tuple(closures), model=model, home=home
        )
    loops = "".join(
        f"\n  <mechkit:loop {' '.join(f'{k}={quoteattr(v)}' for k, v in _attributes(c).items())}/>" for c in closures
    )
    end = urdf.rindex("</robot>")
    text = urdf[:end] + loops + "\n" + urdf[end:]
    if f'xmlns:mechkit="{LOOP_NAMESPACE}"' not in text:
        text = re.sub(r"<robot\b", f'<robot xmlns:mechkit="{LOOP_NAMESPACE}"', text, count=1)
    desc = describe_urdf(text, path, "extended-urdf")
    return dataclasses.replace(desc, actuated=tuple(motors), model=model)


def _read_sidecar(sidecar: Path) -> Sidecar:
    import yaml

    try:
        content = yaml.load(read_text(sidecar), Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader))
    except yaml.YAMLError as err:
        raise MalformedDescription(str(sidecar), f"not YAML: {str(err).splitlines()[0]}") from None
    if not isinstance(content, dict) or not isinstance(content.get("closed_loop"), list):
        raise MalformedDescription(str(sidecar), "needs a list 'closed_loop' of frame pairs")
    pairs = content["closed_loop"]
    for pair in pairs:
        if not (isinstance(pair, list) and len(pair) == 2 and all(isinstance(f, str) for f in pair)):
            raise MalformedDescription(f"{sidecar}: closed_loop", f"{pair!r} is not a pair of frame names")
    kinds = content.get("type")
    if not isinstance(kinds, list) or len(kinds) != len(pairs):
        raise MalformedDescription(f"{sidecar}: type", f"needs one type per closed_loop pair, got {kinds!r}")
    for kind in kinds:
        if kind not in ("3d", "3D", "6d", "6D"):
            raise MalformedDescription(f"{sidecar}: type", f"{kind!r} is not '3d' or '6d'")
    motors = content.get("name_mot")
    if motors is not None and not (isinstance(motors, list) and all(isinstance(m, str) for m in motors)):
        raise MalformedDescription(f"{sidecar}: name_mot", f"must be a list of joint names, got {motors!r}")
    names, types = content.get("joint_name") or [], content.get("joint_type") or []
    for key, value in (("joint_name", names), ("joint_type", types)):
        if not (isinstance(value, list) and all(isinstance(v, str) for v in value)):
            raise MalformedDescription(f"{sidecar}: {key}", f"must be a list of strings, got {value!r}")
    if len(names) != len(types):
        raise MalformedDescription(
            f"{sidecar}: joint_type", f"needs one type per joint_name: {len(types)} types for {len(names)} joints"
        )
    for name, kind in zip(names, types):
        if kind not in ("SPHERICAL", "FIXED") and not (_UJOINT.fullmatch(kind) and kind[-1] != kind[-2]):
            raise MalformedDescription(
                f"{sidecar}: joint_type", f"{kind!r} (for joint {name!r}) is not one of {SUBSTITUTIONS}"
            )
        if names.count(name) > 1:
            raise MalformedDescription(f"{sidecar}: joint_name", f"joint {name!r} is substituted twice")
    return Sidecar(
        [tuple(p) for p in pairs],
        [str(k).lower() for k in kinds],
        None if motors is None else tuple(motors),
        dict(zip(names, types)),
    )


def _substitute(tree: pin.Model, substitutions: dict[str, str], where: str, urdf: str) -> pin.Model:
    """The tree with the sidecar's substitutions applied (FIXED joints locked at zero)."""
    for name in substitutions:
        if not tree.existJointName(name):
            kinds = {f.type for f in tree.frames if f.name == name}
            close = difflib.get_close_matches(name, list(tree.names), n=1, cutoff=0.8)
            why = (
                "is a fixed joint of the URDF: it has no freedom to substitute"
                if pin.FrameType.FIXED_JOINT in kinds
                else f"is a link of {urdf}, not a joint"
                if pin.FrameType.BODY in kinds
                else f"is not a joint of {urdf}"
                + (f" (closest: {close[0]!r})" if close else "")
                + "; Gepetto's loader ignores it and keeps the joint unchanged"
            )
            raise MalformedDescription(where, f"{name!r} {why}")
    if not substitutions:
        return tree
    replace = {tree.getJointId(n): pin.JointModelSpherical() for n, k in substitutions.items() if k == "SPHERICAL"}
    split = {tree.getJointId(n): (k[-2], k[-1]) for n, k in substitutions.items() if k.startswith("UJOINT")}
    lock = [tree.getJointId(n) for n, k in substitutions.items() if k == "FIXED"]
    return rebuild(tree, replace, split, lock)


def _spherical_triplets(model: pin.Model) -> tuple[pin.Model, list[tuple[str, str, str]]]:
    """Gepetto's `simplifyModel` (see the module): chains of three massless-led revolutes through one
    point become a ball joint at the third; returns the model and the triplets (joint names)."""
    data = model.createData()
    pin.framesForwardKinematics(model, data, pin.neutral(model))
    found: list[int] = []
    for j in range(1, model.njoints - 2):
        chain = (j, j + 1, j + 2)
        if any(k in found or k - 1 in found or k - 2 in found for k in chain):
            continue
        if model.parents[j + 1] != j or model.parents[j + 2] != j + 1:
            continue
        columns = [_REVOLUTES.get(model.joints[k].shortname()) for k in chain]
        if None in columns or model.inertias[j].mass >= 1e-5 or model.inertias[j + 1].mass >= 1e-5:
            continue
        axes = [data.oMi[k].rotation[:, c] for k, c in zip(chain, columns)]
        points = [data.oMi[k].translation for k in chain]
        if (
            all(np.linalg.norm(np.cross(axes[a], axes[b])) > 1e-6 for a, b in ((0, 1), (0, 2), (1, 2)))
            and np.linalg.norm(points[0] - points[1]) < 1e-4
            and np.linalg.norm(points[2] - points[1]) < 1e-4
        ):
            found.append(j)
    if not found:
        return model, []
    triplets = [tuple(model.names[k] for k in (j, j + 1, j + 2)) for j in found]
    lock = [k for j in found for k in (j, j + 1)]
    return rebuild(model, {j + 2: pin.JointModelSpherical() for j in found}, {}, lock), triplets


def _one_freedom(model: pin.Model, joint: str, where: str, urdf: str) -> None:
    """`joint` is a one-freedom joint of the built model (a motor, a coupled or a home joint)."""
    if not model.existJointName(joint):
        gone = model.existFrame(joint) or any(model.existJointName(f"{joint}_{a}") for a in "XYZ")
        raise MalformedDescription(
            where,
            f"{joint!r} is not a moving joint of {urdf}"
            + (
                " once substituted (locked, split into a U-joint's two revolutes, or merged into a ball)"
                if gone
                else ""
            ),
        )
    shortname = model.joints[model.getJointId(joint)].shortname()
    if model.joints[model.getJointId(joint)].nv != 1:
        raise MalformedDescription(where, f"{joint!r} is a {shortname} joint: it needs one freedom")


def _frame(model: pin.Model, name: str, where: str, urdf: str) -> pin.Frame:
    """The frame `name` of the model; several frames of that name must be one place."""
    found = [f for f in model.frames if f.name == name]
    if not found:
        raise MalformedDescription(
            where,
            f"frame {name!r} is not a frame of {urdf} (a link, a joint or a fixed joint, after the substitutions)",
        )
    for other in found[1:]:
        if other.parentJoint != found[0].parentJoint or not other.placement.isApprox(found[0].placement, 1e-12):
            raise MalformedDescription(
                where, f"frame name {name!r} names {len(found)} frames of {urdf} at different places"
            )
    return found[0]


def _checked_frames(model: pin.Model, closure: LoopClosure, urdf: str) -> LoopClosure:
    for frame in (closure.frame_a, closure.frame_b):
        _frame(model, frame, f"mechkit:loop {closure.name!r}", urdf)
    return closure


def _closures(model: pin.Model, side: Sidecar, sidecar: Path, urdf: str) -> list[LoopClosure]:
    """The sidecar's pairs as cuts (3d pairs on the same two bodies merged into hinges)."""
    frames = [tuple(_frame(model, f, f"{sidecar}: closed_loop", urdf) for f in pair) for pair in side.pairs]
    used = [False] * len(side.pairs)
    out = []
    for i, ((a, b), kind, (fa, fb)) in enumerate(zip(side.pairs, side.kinds, frames)):
        if [a, b] in [list(p) for p in side.pairs[:i]]:
            raise MalformedDescription(f"{sidecar}: closed_loop {[a, b]}", "the pair is declared twice")
        if used[i]:
            continue
        used[i] = True
        if fa.parentJoint == fb.parentJoint:
            raise MalformedDescription(f"{sidecar}: closed_loop {[a, b]}", "both frames are on one body")
        kind_out, axis = ("weld" if kind == "6d" else "spherical"), None
        if kind == "3d":
            for k in range(i + 1, len(side.pairs)):
                ga, gb = frames[k]
                if (
                    used[k]
                    or side.kinds[k] != "3d"
                    or (ga.parentJoint, gb.parentJoint) != (fa.parentJoint, fb.parentJoint)
                ):
                    continue
                offset = fa.placement.actInv(ga.placement.translation)  # second anchor in frame_a (m)
                if np.linalg.norm(offset) > 1e-9:
                    used[k] = True
                    kind_out, axis = "revolute", offset / np.linalg.norm(offset)
                    break
        out.append(LoopClosure(f"{a}-{b}", kind_out, a, b, axis, explicit_rows=False))
    return out


def _attributes(closure: LoopClosure) -> dict[str, str]:
    out = {"name": closure.name, "frame_a": closure.frame_a, "frame_b": closure.frame_b, "type": closure.kind}
    if closure.axis is not None:
        out["axis"] = " ".join(repr(float(x)) for x in closure.axis)
    return out
