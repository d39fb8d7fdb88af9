"""What a description must be to be physical, whatever its format: finite geometry (placements, joint axes,
gravity) and possible bodies (a mass that is finite and not negative; an inertia about the centre of mass
that is positive semi-definite and satisfies the triangle inequality). Checked on the Pinocchio model every
reader ends in, so a body no reader refused (SDFormat, MJCF, a tree built by hand) cannot reach the
dynamics: a negative mass there gave a motor holding 1e12 N m.

Zero is valid: a massless link (all zero) is a frame, a point mass has a zero inertia, a thin rod a zero
principal moment, and a mass of zero with a non-zero inertia is a rotor whose weight the file counts
elsewhere (URDF+ writes motor rotors so).
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit.base.arguments import LARGEST
from mechkit.base.exceptions import MalformedDescription

#: Relative slack of the principal-moment tests, of their sum (ours): far above rounding, far below anything
#: physical.
INERTIA_RTOL = 1e-12
#: How far a one-freedom joint's motion axis may be from unit length (ours: rounding of a normalised axis;
#: an axis of length 1e-300 is left unnormalised by the URDF parser and scales the joint's column by it).
AXIS_TOL = 1e-9


def check_body(where: str, mass: float, inertia: np.ndarray, shown: object) -> np.ndarray:
    """One body's mass and inertia about its centre of mass, judged.

    Args:
        where: the body, for the error (e.g. "link 'crank'").
        mass: its mass (kg).
        inertia: (3, 3) its inertia about its centre of mass (kg m^2).
        shown: the values as the file gives them, for the error.

    Returns:
        (3, 3) the inertia made symmetric with its round-off negative moments set to zero (Pinocchio refuses
        a moment of -1e-300).

    Raises:
        MalformedDescription: a mass negative, not finite or beyond `LARGEST`, an inertia not finite, beyond
            `LARGEST`, not positive semi-definite, or violating the triangle inequality (each principal moment
            at most the sum of the other two), judged to `INERTIA_RTOL` of the moments' sum.
    """
    if not np.isfinite(mass) or mass < 0:
        raise MalformedDescription(where, f"mass {mass:g} is negative or not finite (kg)")
    if mass > LARGEST:
        raise MalformedDescription(where, f"mass {mass:g} kg is beyond {LARGEST:g}: not a mechanism's")
    if not np.all(np.isfinite(inertia)):
        raise MalformedDescription(where, f"inertia {shown}: not finite")
    if np.max(np.abs(inertia)) > LARGEST:
        raise MalformedDescription(where, f"inertia {shown} is beyond {LARGEST:g} kg m^2: not a mechanism's")
    moments = np.linalg.eigvalsh(0.5 * (inertia + inertia.T))
    slack = INERTIA_RTOL * float(np.sum(np.abs(moments)))
    if moments[0] < -slack:
        raise MalformedDescription(
            where, f"inertia {shown} is not positive semi-definite: principal moment {moments[0]:.6g} kg m^2"
        )
    if moments[0] + moments[1] < moments[2] - slack:
        raise MalformedDescription(
            where,
            f"inertia {shown} violates the triangle inequality: principal moments "
            f"{moments[0]:.6g} + {moments[1]:.6g} < {moments[2]:.6g} kg m^2",
        )
    if moments[0] >= 0:
        return 0.5 * (inertia + inertia.T)
    moments, axes = np.linalg.eigh(0.5 * (inertia + inertia.T))
    return (axes * np.clip(moments, 0.0, None)) @ axes.T


def check_model(model: pin.Model) -> None:
    """Every body of a Pinocchio model possible and its geometry finite.

    Args:
        model: the tree, as a reader built it.

    Raises:
        MalformedDescription: naming the body, joint or frame and the value: a body `check_body` refuses, a
            centre of mass, joint placement, joint axis, frame placement or gravity that is not finite (a
            position beyond `LARGEST` too).
    """
    if not np.all(np.isfinite(model.gravity.vector)):
        raise MalformedDescription("gravity", f"{model.gravity.linear} m/s^2: not finite")
    for j in range(1, model.njoints):
        body = _body_name(model, j)
        inertia = model.inertias[j]
        if not np.all(np.abs(inertia.lever) <= LARGEST):
            raise MalformedDescription(body, f"centre of mass {inertia.lever} m: not finite, or beyond {LARGEST:g}")
        check_body(body, float(inertia.mass), np.array(inertia.inertia), np.array(inertia.inertia).round(12).tolist())
        if not np.all(np.abs(model.jointPlacements[j].homogeneous) <= LARGEST):
            raise MalformedDescription(
                f"joint {model.names[j]!r}", f"its placement is not finite, or beyond {LARGEST:g} m"
            )
    for frame in model.frames:
        if not np.all(np.abs(frame.placement.homogeneous) <= LARGEST):
            raise MalformedDescription(f"frame {frame.name!r}", f"its placement is not finite, or beyond {LARGEST:g} m")
    data = model.createData()
    pin.computeJointJacobians(model, data, pin.neutral(model))
    bad = np.flatnonzero(~np.all(np.isfinite(data.J.reshape(6, -1)), axis=0))
    if bad.size:
        joint = next(j for j in range(1, model.njoints) if model.idx_vs[j] <= bad[0] < model.idx_vs[j] + model.nvs[j])
        raise MalformedDescription(f"joint {model.names[joint]!r}", "its axis is not finite")
    for j in range(1, model.njoints):  # a one-freedom joint's axis of (near) zero length is left unnormalised
        if model.nvs[j] != 1:
            continue
        column = np.asarray(data.J).reshape(6, -1)[:, model.idx_vs[j]]
        turn, slide = float(np.linalg.norm(column[3:])), float(np.linalg.norm(column[:3]))
        if not (abs(turn - 1.0) <= AXIS_TOL or (turn <= AXIS_TOL and abs(slide - 1.0) <= AXIS_TOL)):
            raise MalformedDescription(
                f"joint {model.names[j]!r}", f"its axis is not a direction (length {max(turn, slide):.3g}, not 1)"
            )


def _body_name(model: pin.Model, joint: int) -> str:
    """The link a joint carries (its first body frame), for messages."""
    link = next((f.name for f in model.frames if f.type == pin.FrameType.BODY and f.parentJoint == joint), None)
    return f"link {link!r}" if link is not None else f"the body of joint {model.names[joint]!r}"
