"""A mechanism on a base that moves: its ground body put on root joints of its own.

*fixed*: the mechanism as built (the ground is the world). *moving*: the ground body follows a prescribed
rigid motion, carried by six one-freedom root joints in series from the world, `BASE_JOINTS`: three
prismatic joints along the world axes x, y, z, then three revolute joints about z, y, x (yaw, pitch, roll:
R = Rz(yaw) Ry(pitch) Rx(roll), URDF's rpy). Each is an actuated input, so the core's inverse dynamics
and the simulator's prescribed inputs take the carrier's motion as they take any input, and the reaction
of the last one, `CARRIER_JOINT`, is the wrench the carrier exerts on the mechanism (world axes, about
the ground body's origin). A free-flyer cannot carry it: the core's motors drive one-freedom joints only.
*floating*: the ground body is a free body (a spacecraft bus: mass and inertia given, ours) on a passive
free-flyer root `FLOATING_JOINT`. Gravity can be set for any base (zero in orbit); it stays in world axes.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np
import pinocchio as pin

from mechkit import core
from mechkit.base import arguments
from mechkit.base.exceptions import InvalidArgument
from mechkit.mechanism import Mechanism

BASES = ("fixed", "moving", "floating")
#: The moving base's root joints, world to ground body: x, y, z (m), yaw, pitch, roll (rad).
BASE_JOINTS = ("base_x", "base_y", "base_z", "base_yaw", "base_pitch", "base_roll")
#: The root joint whose reaction is the carrier's wrench on the mechanism.
CARRIER_JOINT = BASE_JOINTS[-1]
#: The floating base's free-flyer root.
FLOATING_JOINT = "base_free"
#: The body frame of the carried ground (on the last root joint).
CARRIER_FRAME = "carrier"
_CHAIN = (pin.JointModelPX, pin.JointModelPY, pin.JointModelPZ, pin.JointModelRZ, pin.JointModelRY, pin.JointModelRX)


def base_inertia_of(value: pin.Inertia | Sequence | None) -> pin.Inertia:
    """A base body's inertia from what a user gives.

    Args:
        value: a `pin.Inertia`, or (mass kg, (Ixx, Iyy, Izz) kg m^2) of a body centred at the ground body's
            origin with its principal axes along the ground's, or None (no added inertia).

    Returns:
        The inertia, in the ground body's frame.

    Raises:
        InvalidArgument: a negative or non-finite mass or moment, or another shape.
    """
    if value is None:
        return pin.Inertia.Zero()
    if isinstance(value, pin.Inertia):
        return pin.Inertia(value)
    try:
        mass, moments = float(value[0]), np.asarray(value[1], dtype=float)
    except (TypeError, ValueError, IndexError):
        raise InvalidArgument("base_inertia", value, "expected a pin.Inertia or (mass, (Ixx, Iyy, Izz))") from None
    if len(value) != 2 or moments.shape != (3,) or not np.all(np.isfinite(moments)) or not np.isfinite(mass):
        raise InvalidArgument("base_inertia", value, "expected (mass kg, (Ixx, Iyy, Izz) kg m^2), finite")
    if mass < 0 or np.any(moments < 0) or 2 * moments.max() > moments.sum() + 1e-12 * moments.sum():
        raise InvalidArgument("base_inertia", value, "mass and moments must be >= 0 and the moments a triangle")
    return pin.Inertia(mass, np.zeros(3), np.diag(moments))


def _roots(base: str, inertia: pin.Inertia) -> tuple[pin.Model, int]:
    """The root joints alone (the ground's inertia on the last), and the carrier frame's id."""
    roots, parent = pin.Model(), 0
    chain = (pin.JointModelFreeFlyer,) if base == "floating" else _CHAIN
    names = (FLOATING_JOINT,) if base == "floating" else BASE_JOINTS
    for k, (joint, name) in enumerate(zip(chain, names)):
        parent = roots.addJoint(parent, joint(), pin.SE3.Identity(), name)
        roots.appendBodyToJoint(parent, inertia if k == len(chain) - 1 else pin.Inertia.Zero(), pin.SE3.Identity())
    frame = roots.addFrame(pin.Frame(CARRIER_FRAME, parent, 0, pin.SE3.Identity(), pin.FrameType.BODY))
    return roots, frame


def with_base(
    mech: Mechanism,
    base: str = "fixed",
    *,
    base_inertia: pin.Inertia | Sequence | None = None,
    gravity: Sequence[float] | None = None,
) -> Mechanism:
    """The mechanism on a fixed, moving or floating base (see the module's docstring).

    The new mechanism keeps the closures, couplings, springs, actuators, home inputs, guess, scenes and
    motion laws (their poses with the base at the world's origin, each law as sampled on the fixed
    ground); its root joints sit at the identity at home.

    Args:
        mech: the mechanism on its fixed ground.
        base: "fixed", "moving" or "floating".
        base_inertia: the base body's added inertia (`base_inertia_of`; a bus's, ours), on the ground
            body's own (the universe's in the file); not for a fixed base.
        gravity: (3,) world gravity (m/s^2; (0, 0, 0) in orbit), or None (the model's).

    Returns:
        The mechanism (the same object for a fixed base with no new gravity).

    Raises:
        InvalidArgument: an unknown base, an inertia for a fixed base, a floating base without mass, a
            gravity that is not 3 finite numbers.
    """
    arguments.option("base", base, BASES)
    g = None if gravity is None else arguments.array("gravity", gravity, 3, batch=False)
    if base == "fixed" and base_inertia is not None:
        raise InvalidArgument("base_inertia", base_inertia, "a fixed base is the world: it has no inertia to add")
    if base == "fixed" and g is None:
        return mech
    if base == "fixed":
        model = pin.Model(mech.model)
    else:
        inertia = mech.model.inertias[0] + base_inertia_of(base_inertia)
        if base == "floating" and not inertia.mass > 0:
            raise InvalidArgument("base_inertia", base_inertia, "a floating base needs a mass (the bus's)")
        roots, frame = _roots(base, inertia)
        model = pin.appendModel(roots, mech.model, frame, pin.SE3.Identity())
    if g is not None:
        model.gravity = pin.Motion(np.asarray(g, dtype=float), np.zeros(3))
    return _rebuilt(mech, model, base)


def _rebuilt(mech: Mechanism, model: pin.Model, base: str) -> Mechanism:
    """The mechanism over a new tree (the old one's joints, under the base's roots)."""
    cm = mech.closure_model
    added = {"fixed": (), "moving": BASE_JOINTS, "floating": ()}[base]
    actuated = tuple(added) + tuple(cm.actuated)
    closure_model = core.ClosureModel(model, mech.closures, cm.couplings, actuated, cm.actuators, None)
    spec, params = mech.spec, mech.params
    home, guess = dict(spec.home(params)), dict(spec.guess(params)) if spec.guess is not None else {}
    home.update(dict.fromkeys(added, 0.0))
    lead = model.nq - mech.model.nq
    pad = pin.neutral(model)[:lead]

    def poses(scene):
        return lambda _m: [np.concatenate([pad, q]) for q in scene(mech)]

    def times(scene_time):
        return lambda _m, n: scene_time(mech, n)

    def sampled(law):  # a motion law of the mechanism on its ground, its warm starts with the base at home
        def sample(_m, n):
            out = law.sample(mech, n)
            guesses = None if out.guesses is None else np.hstack([np.tile(pad, (len(out.guesses), 1)), out.guesses])
            return dataclasses.replace(out, guesses=guesses)

        return dataclasses.replace(law, sample=sample)

    new_spec = dataclasses.replace(
        spec,
        actuated=actuated,
        gruebler_dof=closure_model.structure.kutzbach,
        home=lambda _p: dict(home),
        guess=(lambda _p: dict(guess)) if guess else None,
        scenes={name: poses(fn) for name, fn in spec.scenes.items()},
        scene_times={name: times(fn) for name, fn in spec.scene_times.items()},
        summary=f"{spec.summary} (on a {base} base)",
        bench_methods=(),
        bench_references=(),
        bench_states=None,
        failure_studies=(),
        motion_laws={name: sampled(law) for name, law in spec.motion_laws.items()},
        design_metrics=(),
        studies={},
        self_checks=None,
    )
    return Mechanism(new_spec, params, closure_model, None, mech.springs.springs, mech.urdf or mech.source_urdf)


def base_of(mech: Mechanism) -> str:
    """Which base a mechanism stands on.

    Args:
        mech: a mechanism.

    Returns:
        "moving" (it has the root joints `BASE_JOINTS`), "floating" (`FLOATING_JOINT`) or "fixed".
    """
    names = set(mech.model.names)
    if set(BASE_JOINTS) <= names:
        return "moving"
    return "floating" if FLOATING_JOINT in names else "fixed"
