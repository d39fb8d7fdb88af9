"""Mechanisms whose trees have joints URDF cannot write, built in Pinocchio directly (test fixtures; the
values are ours): an RSSR spatial four-bar with ball joints at both coupler ends, and a five-bar on a
floating base (free-flyer) fixed to the ground by a weld closure."""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit import core
from mechkit.loading import from_description
from mechkit.mechanism import Mechanism
from mechkit.sources import Description


def _rod(model: pin.Model, joint: int, length: float, axis: np.ndarray, mass: float = 0.4) -> None:
    """A uniform rod of `length` (m) along `axis` (unit, joint frame) from the joint origin."""
    inertia = pin.Inertia.FromCylinder(mass, 0.01, length)
    z = np.array([0.0, 0.0, 1.0])
    rotation = pin.Quaternion.FromTwoVectors(z, axis).matrix()
    model.appendBodyToJoint(joint, pin.SE3(rotation, 0.5 * length * axis) * inertia, pin.SE3.Identity())


def _frame(model: pin.Model, name: str, joint: int, where: np.ndarray) -> None:
    model.addFrame(pin.Frame(name, joint, pin.SE3(np.eye(3), np.asarray(where, dtype=float)), pin.FrameType.OP_FRAME))


def rssr() -> Mechanism:
    """RSSR: crank (revolute about z at the origin), coupler on a ball joint at the crank's tip, rocker
    (revolute about x at (0.3, 0.25, 0.1)), the coupler's far end on a ball (the cut) at the rocker's
    tip. Two freedoms: the crank's and the coupler's idle spin about its own axis."""
    model = pin.Model()
    crank = model.addJoint(0, pin.JointModelRZ(), pin.SE3.Identity(), "crank")
    _rod(model, crank, 0.1, np.array([1.0, 0.0, 0.0]))
    coupler = model.addJoint(crank, pin.JointModelSpherical(), pin.SE3(np.eye(3), np.array([0.1, 0.0, 0.0])), "ball_a")
    direction = np.array([0.2, 0.25, 0.25])
    length = float(np.linalg.norm(direction))
    _rod(model, coupler, length, direction / length)
    _frame(model, "coupler_end", coupler, direction)
    rocker = model.addJoint(0, pin.JointModelRX(), pin.SE3(np.eye(3), np.array([0.3, 0.25, 0.1])), "rocker")
    _rod(model, rocker, 0.15, np.array([0.0, 0.0, 1.0]))
    _frame(model, "rocker_end", rocker, np.array([0.0, 0.0, 0.15]))
    ball = core.LoopClosure("ball_b", "spherical", "rocker_end", "coupler_end")
    guess = {"ball_a": (0.1, -0.2, 0.3), "rocker": 0.2}
    return from_description(
        Description("rssr", None, ("crank",), {"crank": 0.3}, guess, model=model, closures=(ball,), format="pinocchio")
    )


def floating_five_bar() -> Mechanism:
    """A planar five-bar (x-z plane, pins along y) whose base is a floating body (free-flyer), welded to
    the ground by a closure: ten coordinates of velocity, eight rows, two freedoms (the cranks)."""
    model = pin.Model()
    base = model.addJoint(0, pin.JointModelFreeFlyer(), pin.SE3.Identity(), "base")
    model.appendBodyToJoint(base, pin.Inertia.FromBox(2.0, 0.3, 0.05, 0.05), pin.SE3.Identity())
    _frame(model, "base_anchor", base, np.zeros(3))
    _frame(model, "ground_anchor", 0, np.zeros(3))
    lengths = {"prox1": 0.12, "prox2": 0.12, "dist1": 0.2, "dist2": 0.2}
    tips = []
    for prox, dist, x in (("prox1", "dist1", -0.1), ("prox2", "dist2", 0.1)):  # depth first, as Pinocchio needs
        crank = model.addJoint(base, pin.JointModelRY(), pin.SE3(np.eye(3), np.array([x, 0.0, 0.0])), prox)
        _rod(model, crank, lengths[prox], np.array([0.0, 0.0, 1.0]), 0.3)
        tip = model.addJoint(crank, pin.JointModelRY(), pin.SE3(np.eye(3), np.array([0.0, 0.0, 0.12])), dist)
        _rod(model, tip, lengths[dist], np.array([0.0, 0.0, 1.0]), 0.3)
        tips.append(tip)
    _frame(model, "tip_a", tips[0], np.array([0.0, 0.0, 0.2]))
    _frame(model, "tip_b", tips[1], np.array([0.0, 0.0, 0.2]))
    weld = core.LoopClosure("ground_weld", "weld", "ground_anchor", "base_anchor")
    pin_joint = core.LoopClosure("C", "revolute", "tip_a", "tip_b", axis=np.array([0.0, 1.0, 0.0]), rows="planar")
    guess = {"dist1": 0.6, "dist2": -0.6}
    return from_description(
        Description(
            "floating_five_bar",
            None,
            ("prox1", "prox2"),
            {"prox1": -0.3, "prox2": 0.3},
            guess,
            model=model,
            closures=(weld, pin_joint),
            format="pinocchio",
        )
    )
