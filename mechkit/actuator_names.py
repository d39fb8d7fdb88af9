"""Actuators named where input joints are: an actuator's name and value mapped to the joint it drives.

An actuator acts as the generalised force coefficient * u on each joint of its transmission
(`mechkit.core.Actuator`), so by virtual work its position is x = sum coefficient * q over them. One
joint: q = x / coefficient (a URDF transmission, an SDF gearbox input, an MJCF joint actuator with its
gear). Several joints tied equal by the file's couplings (a tendon over joints an identity equality
ties, as the Robotiq 2F-85's fingers): q = x / sum coefficient on the first of them. Otherwise the
actuator fixes no single joint and is refused by name. A URDF `<transmission>` of one joint is also
known by its own name (`transmission_names`), its position the joint's value.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from mechkit.base.exceptions import InvalidArgument
from mechkit.core import ClosureModel
from mechkit.sources.urdf import parse_xml


def transmission_names(urdf: str | None) -> dict[str, str]:
    """The URDF's one-joint `<transmission>`s: name -> the joint it drives (those named after no joint).

    Args:
        urdf: the URDF text (None: no URDF).

    Returns:
        Transmission name -> joint name.
    """
    if urdf is None:
        return {}
    root = parse_xml(urdf)
    joints = {j.get("name") for j in root.findall("joint")}
    out = {}
    for t in root.findall("transmission"):
        driven = [j.get("name") for j in t.findall("joint")]
        if len(driven) == 1 and t.get("name") and t.get("name") not in joints:
            out[t.get("name")] = driven[0]
    return out


def _tied(cm: ClosureModel, a: str, b: str) -> bool:
    """Whether a coupling of the model makes joints a and b equal (x_b = x_a, both of coefficient 1)."""
    for c in cm.couplings:
        pair = {c.follower[0][0], c.leader[0][0]} if len(c.follower) == 1 and len(c.leader) == 1 else set()
        identity = tuple(c.polynomial[:2]) == (0.0, 1.0) and not any(c.polynomial[2:])
        if pair == {a, b} and identity and c.follower[0][1] == c.leader[0][1] == 1.0 and c.follower_ref == c.leader_ref:
            return True
    return False


def driven_joint(cm: ClosureModel, arg: str, actuator: str) -> tuple[str, float]:
    """The joint an actuator fixes and the factor from the actuator's position to the joint's value.

    Args:
        cm: the closure model (its actuators and couplings).
        arg: the argument naming the actuator (for the error).
        actuator: one of `cm.actuators`' names.

    Returns:
        (joint, k) with the joint's value = k * the actuator's position (rad or m).

    Raises:
        InvalidArgument: the actuator's transmission fixes no single joint (several joints not tied equal).
    """
    (act,) = [a for a in cm.actuators if a.name == actuator]
    joints = [j for j, _ in act.joints]
    total = sum(c for _, c in act.joints)
    if len(joints) == 1 or (total != 0.0 and all(_tied(cm, joints[0], j) for j in joints[1:])):
        return joints[0], 1.0 / total
    raise InvalidArgument(
        arg,
        actuator,
        f"actuator {actuator!r} drives joints {joints} that the file does not tie equal: give their values by joint",
    )


def known_names(cm: ClosureModel, aliases: Mapping[str, str]) -> list[str]:
    """The names an input may take: the model's joints, then the actuators not named after a joint.

    Args:
        cm: the closure model.
        aliases: other names of joints (`transmission_names`).

    Returns:
        Joint names, then actuator names.
    """
    joints = list(cm.model.names[1:])
    return joints + [a.name for a in cm.actuators if a.name not in joints] + [a for a in aliases if a not in joints]


def check_known(cm: ClosureModel, arg: str, names: Any, aliases: Mapping[str, str]) -> None:
    """Refuse a name that is neither a joint nor an actuator, listing both.

    Args:
        cm: the closure model.
        arg: the argument's name (for the error).
        names: the names given (a mapping's keys or a sequence; anything else is left to the joint checks).
        aliases: other names of joints (`transmission_names`).

    Raises:
        InvalidArgument: an unknown name.
    """
    if isinstance(names, str) or not isinstance(names, Mapping | Sequence):
        return
    known = known_names(cm, aliases)
    for name in names:
        if isinstance(name, str) and name not in known:
            joints = list(cm.model.names[1:])
            raise InvalidArgument(
                arg,
                list(names),
                f"{name!r} is neither a joint nor an actuator; joints: {joints}; actuators: "
                f"{[n for n in known if n not in joints]}",
            )


def to_joints(cm: ClosureModel, arg: str, values: Mapping[str, Any], aliases: Mapping[str, str]) -> dict[str, Any]:
    """Input values keyed by joints or actuators, keyed by joints.

    Args:
        cm: the closure model.
        arg: the argument's name (for the error).
        aliases: other names of joints (`transmission_names`).
        values: name -> value (rad or m for a joint; the actuator's position for an actuator).

    Returns:
        Joint -> value.

    Raises:
        InvalidArgument: an actuator fixing no single joint, or two names giving one joint.
    """
    joints, out = set(cm.model.names[1:]), {}
    for name, value in values.items():
        if name in joints or name in aliases:
            joint, k = aliases.get(name, name), 1.0
        else:
            joint, k = driven_joint(cm, arg, name)
        if joint in out:
            raise InvalidArgument(arg, list(values), f"joint {joint!r} is given twice (by {name!r} and before)")
        out[joint] = value * k
    return out


def to_joint_names(cm: ClosureModel, arg: str, names: Sequence[str], aliases: Mapping[str, str]) -> list[str]:
    """Input names (joints or actuators) as the joints they fix.

    Args:
        cm: the closure model.
        arg: the argument's name (for the error).
        aliases: other names of joints (`transmission_names`).
        names: joint or actuator names (checked against `known_names` before).

    Returns:
        The joints, in order.

    Raises:
        InvalidArgument: an actuator fixing no single joint, or two names giving one joint.
    """
    return list(to_joints(cm, arg, dict.fromkeys(names, 0.0), aliases))
