"""An MJCF (MuJoCo) file: compiled by MuJoCo, read into a Pinocchio model with closure records.

MuJoCo resolves the format (defaults, angle units, orientations, inertias from geoms and meshes);
this package reads the compiled model: its tree (`tree`: hinge, slide, ball and free joints, the
compiled inertias, sites, armature, gravity), its equalities, springs and actuators (`constraints`);
the simulator reads spatial tendons between two sites as forces (`spatial_tendons`).
Pinocchio's q equals MuJoCo's qpos (a ball's and a free joint's quaternion reordered x, y, z, w).
The guess is the keyframe named "home" when the file has one (Menagerie's convention for a robot's
rest pose), else qpos0; the home inputs are the guess's values of the driven joints (a ball's or
free joint's rotation as a rotation vector).
A tree of hinges and slides is also written as URDF text (`Description.urdf`), else that is None.
"""

from __future__ import annotations

import contextlib
import warnings
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import MalformedDescription, MethodUnavailable, MuJoCoWarning
from mechkit.sources.description import Description, read_text
from mechkit.sources.mjcf import spatial_tendons
from mechkit.sources.mjcf.constraints import actuation, check_tendons, equalities, springs
from mechkit.sources.mjcf.tree import Tree, build_tree
from mechkit.sources.pinocchio_tree import tree_urdf
from mechkit.sources.urdf import parse_xml

__all__ = ["read_mjcf"]


@contextlib.contextmanager
def _warnings_kept(mujoco: Any) -> Iterator[list[str]]:
    """MuJoCo's warnings while compiling, kept in a list instead of printed on standard output (where they
    would break `--json`) and appended to a MUJOCO_LOG.TXT in the working directory."""
    said: list[str] = []
    previous = mujoco.get_mju_user_warning()
    mujoco.set_mju_user_warning(said.append)
    try:
        yield said
    finally:
        mujoco.set_mju_user_warning(previous)


def read_mjcf(path: Path) -> Description:
    """The description in an MJCF file (see the package docstring).

    Args:
        path: an MJCF file; its meshes and other assets where the file says (MuJoCo reads them).

    Returns:
        `Description` with `model` (and `urdf` for a tree of hinges and slides), closures,
        couplings, springs, actuators, guess (the keyframe "home" if there is one, else qpos0) and
        home (the guess's values of the driven joints).

    Raises:
        MethodUnavailable: MuJoCo is not installed (`pip install mechkit[peers]`).
        MalformedDescription: not MJCF, MuJoCo cannot compile it, it has no joint, or it uses what
            mechkit does not read (`mechkit.sources.mjcf.constraints`), each named.

    Warns:
        MuJoCoWarning: each warning MuJoCo gave while compiling (one line each on the command line).
    """
    root = parse_xml(read_text(path), str(path))
    if root.tag != "mujoco":
        raise MalformedDescription(str(path), f"root element <{root.tag}>: an MJCF file starts with <mujoco>")
    try:
        import mujoco
    except ImportError:
        raise MethodUnavailable("MJCF reading", "needs MuJoCo: pip install 'mechkit[peers]'") from None
    try:
        with _warnings_kept(mujoco) as said:
            mm = mujoco.MjModel.from_xml_path(str(path))
    except ValueError as err:
        where = "; ".join(line.strip() for line in str(err).strip().splitlines()[:2])
        raise MalformedDescription(str(path), f"MuJoCo could not compile it: {where}") from None
    for text in said:
        warnings.warn(MuJoCoWarning(f"{path.name}: MuJoCo: {text.strip()}"), stacklevel=2)
    if mm.njnt == 0:
        raise MalformedDescription(str(path), "the model has no joint: nothing moves")
    tree = build_tree(mujoco, mm, root.get("model") or path.name.split(".")[0])
    closures, couplings = equalities(mm, tree)
    check_tendons(mm, tree)
    spatial_tendons.read(mujoco, mm)  # refuses, by name, the spatial tendons and actuators it cannot read
    actuated, actuators = actuation(mm, tree)
    key = mujoco.mj_name2id(mm, mujoco.mjtObj.mjOBJ_KEY, "home")
    guess = _joint_values(mm, tree, mm.key_qpos[key] if key >= 0 else mm.qpos0)
    driven = [j for a in actuators for j, _ in a.joints] + [j for j in actuated if j in guess]
    return Description(
        tree.model.name,
        tree_urdf(tree.model, closures),
        actuated,
        {j: guess[j] for j in driven},
        guess,
        path,
        "mjcf",
        closures=closures,
        model=tree.model,
        couplings=couplings,
        springs=springs(mm, tree),
        actuators=actuators,
        pose="the keyframe 'home'" if key >= 0 else "qpos0",
    )


def _joint_values(mm, tree: Tree, qpos: np.ndarray) -> dict[str, float | tuple[float, ...]]:
    """A MuJoCo qpos (nq,) by joint: a hinge's or slide's value (rad or m, as MuJoCo counts it: the
    tree's q), a ball's rotation vector, a free joint's position and rotation vector."""
    out: dict[str, float | tuple[float, ...]] = {}
    for j, name in enumerate(tree.names["joint"]):
        q = np.asarray(qpos[mm.jnt_qposadr[j] :], dtype=float)
        kind = int(mm.jnt_type[j])
        if kind in (2, 3):
            out[name] = float(q[0])
        else:
            at = 3 if kind == 0 else 0
            w, x, y, z = q[at : at + 4]
            rotation = tuple(float(c) for c in pin.log3(pin.Quaternion(w, x, y, z).normalized().matrix()))
            out[name] = tuple(float(c) for c in q[:3]) + rotation if kind == 0 else rotation
    return out
