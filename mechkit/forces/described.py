"""What a description file says about forces and limits beyond the springs the readers already give.

- URDF: `<dynamics damping friction>` of a moving joint (a viscous damper, N m s/rad or N s/m, and
  a constant friction, N m or N) and `<limit lower upper effort velocity>` (joint limits, rad or m,
  and an actuated joint's motor envelope: stall effort and no-load rate). The registered mechanisms'
  limits are wide (+-25 rad, 1e6, 1e3; +-1e9 rad on a joint that turns fully, as the four-bar's crank):
  no motion of their scenes reaches them.
- MJCF (compiled by MuJoCo): `frictionloss` (constant friction), `range` of a limited joint, an
  actuator's `forcerange` (its stall effort; MJCF has no speed limit), and the spatial tendons between
  two sites with their springs, dampers and actuators (`mechkit.sources.mjcf.spatial_tendons`).
  Stiffness, springref and damping are the reader's joint springs (`Mechanism.springs`).
- URDF: `<mechkit:strut>` point-to-point springs, dampers and forces (`mechkit.sources.urdf_struts`), and
  Drake bushings loaded compliant (`mechkit.forces.bushing`).
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

import pinocchio as pin

from mechkit.base.exceptions import MalformedDescription, MethodUnavailable
from mechkit.core import JointSpring
from mechkit.forces.bushing import bushing_forces
from mechkit.forces.coulomb import SPEED_THRESHOLD, CoulombFriction
from mechkit.forces.point_to_point import PointToPoint, point_to_point
from mechkit.forces.springs import JointSprings
from mechkit.sources.drake_elements import Bushing, bushings


@dataclass(frozen=True)
class Described:
    """Forces and limits read from a description.

    Attributes:
        dampers: joint -> viscous damping (N m s/rad or N s/m).
        friction: joint -> constant friction (N m or N).
        limits: joint -> (lower, upper) (rad or m).
        motors: joint or actuator -> (stall effort (N m or N), no-load rate (rad/s or m/s)); inf where none.
        struts: point-to-point springs, dampers and forces (`PointToPoint`).
        bushings: Drake bushings loaded compliant (`mechkit.forces.bushing`).
    """

    dampers: dict[str, float] = field(default_factory=dict)
    friction: dict[str, float] = field(default_factory=dict)
    limits: dict[str, tuple[float, float]] = field(default_factory=dict)
    motors: dict[str, tuple[float, float]] = field(default_factory=dict)
    struts: list[PointToPoint] = field(default_factory=list)
    bushings: list[Bushing] = field(default_factory=list)

    def elements(self, model: pin.Model, threshold: float = SPEED_THRESHOLD) -> list:
        """The dampers and the friction as force elements.

        Args:
            model: the tree's Pinocchio model (the joints named here must be its).
            threshold: the friction's regularisation rate (rad/s or m/s, > 0; `mechkit.forces.coulomb`).

        Returns:
            A `JointSprings` of the dampers, a `CoulombFriction` of the friction, each only where the file
            declares some, a `PointToPointForce` per strut and a `BushingForce` per compliant bushing (an
            empty list where it declares none).

        Raises:
            InvalidParameters: a strut's frame the model does not have, a threshold not > 0.
        """
        out: list = []
        if self.dampers:
            out.append(
                JointSprings(model, [JointSpring(j, damping=d) for j, d in self.dampers.items()], "joint dampers")
            )
        if self.friction:
            out.append(CoulombFriction(model, self.friction, threshold))
        return out + point_to_point(model, self.struts) + bushing_forces(model, self.bushings)


def _float(element: ET.Element, attribute: str, default: float, where: str) -> float:
    text = element.get(attribute)
    try:
        value = default if text is None else float(text)
    except ValueError:
        raise MalformedDescription(where, f"{attribute}={text!r} is not a number") from None
    if not math.isfinite(value) and text is not None:
        raise MalformedDescription(where, f"{attribute}={text!r} is not finite")
    return value


def from_urdf(urdf: str, model: pin.Model, actuated: tuple[str, ...] = ()) -> Described:
    """The dampers, friction, limits and motor envelopes of a URDF's moving joints that the model has.

    Args:
        urdf: the URDF text.
        model: the tree's Pinocchio model (joints it lacks are skipped).
        actuated: the actuated joints (their `<limit effort velocity>` give the motor envelopes).

    Returns:
        The `Described` forces and limits.

    Raises:
        MalformedDescription: a value that is not a finite number.
    """
    from mechkit.sources.urdf_struts import parse_struts  # here: the URDF reader imports the forces

    root = ET.fromstring(urdf)
    out = Described(struts=list(parse_struts(root)), bushings=[b for b in bushings(root) if b.compliant])
    for joint in root.findall("joint"):
        name, kind = joint.get("name"), joint.get("type")
        if kind == "fixed" or not model.existJointName(name or ""):
            continue
        where = f"URDF joint {name!r}"
        dynamics = joint.find("dynamics")
        if dynamics is not None:
            damping, friction = _float(dynamics, "damping", 0.0, where), _float(dynamics, "friction", 0.0, where)
            if damping:
                out.dampers[name] = damping
            if friction:
                out.friction[name] = friction
        limit = joint.find("limit")
        if limit is not None and kind in ("revolute", "prismatic"):
            lower, upper = _float(limit, "lower", 0.0, where), _float(limit, "upper", 0.0, where)
            if lower < upper:
                out.limits[name] = (lower, upper)
            if name in actuated:
                out.motors[name] = (
                    _float(limit, "effort", math.inf, where) or math.inf,
                    _float(limit, "velocity", math.inf, where) or math.inf,
                )
    return out


def from_mjcf(path: Path, model: pin.Model) -> Described:
    """The friction losses, limited ranges and actuator force ranges of an MJCF file (compiled by MuJoCo)
    of the one-freedom joints the model has.

    Args:
        path: the MJCF file.
        model: the tree's Pinocchio model (joints it lacks are skipped).

    Returns:
        The `Described` forces and limits (motors: stall effort from `forcerange`, no-load rate inf).

    Raises:
        MethodUnavailable: MuJoCo is not installed.
        MalformedDescription: MuJoCo cannot compile the file.
    """
    try:
        import mujoco
    except ImportError:
        raise MethodUnavailable("MJCF forces", "needs MuJoCo: pip install 'mechkit[peers]'") from None
    try:
        mm = mujoco.MjModel.from_xml_path(str(path))
    except ValueError as err:
        raise MalformedDescription(
            str(path), f"MuJoCo could not compile it: {str(err).strip().splitlines()[0]}"
        ) from None
    out = Described()
    one = (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE))
    for j in range(mm.njnt):
        name = mujoco.mj_id2name(mm, mujoco.mjtObj.mjOBJ_JOINT, j)
        if int(mm.jnt_type[j]) not in one or not name or not model.existJointName(name):
            continue
        loss = float(mm.dof_frictionloss[mm.jnt_dofadr[j]])
        if loss:
            out.friction[name] = loss
        if mm.jnt_limited[j]:
            out.limits[name] = (float(mm.jnt_range[j, 0]), float(mm.jnt_range[j, 1]))
    from mechkit.sources.mjcf import spatial_tendons  # here: the sources import the forces

    out.struts.extend(spatial_tendons.read(mujoco, mm))
    for a in range(mm.nu):
        name = mujoco.mj_id2name(mm, mujoco.mjtObj.mjOBJ_ACTUATOR, a) or f"actuator{a}"
        if mm.actuator_forcelimited[a]:
            out.motors[name] = (
                float(max(abs(mm.actuator_forcerange[a, 0]), abs(mm.actuator_forcerange[a, 1]))),
                math.inf,
            )
    return out


def read(source: str | Path | None, urdf: str | None, model: pin.Model, actuated: tuple[str, ...] = ()) -> Described:
    """What a mechanism's description says: from an MJCF file when `source` is one, else from its URDF text.

    Args:
        source: the description file (an `.xml` or `.mjcf` path is read as MJCF), or None.
        urdf: the URDF text (`Mechanism.urdf`), or None.
        model: the tree's Pinocchio model.
        actuated: the actuated joints (URDF motor envelopes).

    Returns:
        The `Described` forces and limits; empty without either source.

    Raises:
        MethodUnavailable: an MJCF source and MuJoCo is not installed.
        MalformedDescription: a value that is not a finite number, or an MJCF file MuJoCo cannot compile.
    """
    if source is not None and str(source).endswith((".xml", ".mjcf")):
        return from_mjcf(Path(source), model)
    return from_urdf(urdf, model, actuated) if urdf else Described()
