"""How much of a carrier's tilt reaches a held body at each frequency, with the drives as position servos.

The carrier oscillates about one root joint (roll by default): c(t) = A sin(w t). The drives follow the
inputs that would hold the body (`hold_pose`, tabulated over the carrier's angle once: `Holding table`)
as position servos of a given bandwidth (`mechkit.bases.servo`), in a simulation of the whole mechanism
on its moving base (gravity, the carrier's accelerations, the servos' lag). The residual tilt is the
amplitude at w of the body's tilt about the carrier's axis (a least-squares sine fit over the periods
after the first), and the ratio is residual tilt over A. A servo on an inertia alone (its rotor's) follows
its command (value and rate) as H = (2 zeta w_b s + w_b^2) / (s^2 + 2 zeta w_b s + w_b^2) and leaves
|1 - H(jw)| A = w^2 / |w_b^2 - w^2 + 2 j zeta w_b w| A (`servo_theory`); gravity and the links' own
inertia move the simulated ratio away from it (the platform's inertia filters the highest frequencies).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin
import scipy.interpolate

from mechkit.base.exceptions import InvalidArgument
from mechkit.bases.carrier import BASE_JOINTS, with_base
from mechkit.bases.holding import hold_pose
from mechkit.bases.servo import PositionServo
from mechkit.mechanism import Mechanism

#: The carrier's angles tabulated for the holding inputs, over the amplitude.
TABLE_POINTS = 41


def on_carrier(mech: Mechanism, rotor_inertia: float) -> Mechanism:
    """The mechanism on a moving base, each of its actuated joints' motor with a rotor inertia (Pinocchio's
    armature: the rotor's inertia reflected through its gearbox, on the joint's own acceleration).

    Args:
        mech: the mechanism on its fixed ground.
        rotor_inertia: each motor's reflected rotor inertia (kg m^2 or kg, >= 0; ours where a study sets it).

    Returns:
        The new mechanism (its own model; `mech` is unchanged).

    Raises:
        InvalidArgument: a rotor inertia not finite and >= 0.
    """
    if not (np.isfinite(rotor_inertia) and rotor_inertia >= 0):
        raise InvalidArgument("rotor_inertia", rotor_inertia, "must be finite and >= 0")
    moving = with_base(mech, "moving")
    for joint in mech.actuated:
        moving.model.armature[moving.v_index(joint)] = rotor_inertia
    return moving


@dataclass(frozen=True)
class HoldingTable:
    """The holding inputs over the carrier's angle (a cubic spline through `TABLE_POINTS` solutions).

    Attributes:
        carrier: the root joint the carrier turns about.
        frame: the held body's frame; axis: (its axis, the world direction) kept.
        splines: input joint -> spline of the carrier's angle (rad -> rad or m).
        worst_tilt: the largest tilt (rad) the tabulated solutions leave.
    """

    carrier: str
    frame: str
    axis: tuple
    splines: dict
    worst_tilt: float

    def command(self, angle: float, rate: float) -> dict[str, tuple[float, float]]:
        """The inputs holding the body at a carrier angle, and their rates.

        Args:
            angle: the carrier's angle (rad).
            rate: its rate (rad/s).

        Returns:
            input joint -> (value, rate).
        """
        return {j: (float(s(angle)), float(s(angle, 1)) * rate) for j, s in self.splines.items()}


def holding_table(
    mech: Mechanism, frame: str, axis: tuple, amplitude: float, carrier: str = "base_roll"
) -> HoldingTable:
    """Tabulate the inputs holding a body's axis over a carrier's angle in [-1.2 A, 1.2 A].

    Args:
        mech: a mechanism on a moving base.
        frame: the held body's frame.
        axis: (body axis, world direction) to keep (`hold_pose`).
        amplitude: the carrier's largest angle A (rad, > 0).
        carrier: the root joint the carrier turns about (`BASE_JOINTS`).

    Returns:
        The `HoldingTable`.

    Raises:
        InvalidArgument: an amplitude not > 0, a carrier that is not a root joint.
    """
    if carrier not in BASE_JOINTS[3:] or carrier not in mech.model.names:
        raise InvalidArgument("carrier", carrier, f"expected a rotation root joint of a moving base: {BASE_JOINTS[3:]}")
    if not (np.isfinite(amplitude) and amplitude > 0):
        raise InvalidArgument("amplitude", amplitude, "must be a finite angle > 0 (rad)")
    angles = np.linspace(-1.2 * amplitude, 1.2 * amplitude, TABLE_POINTS)
    held, start = [], None
    for angle in angles:
        held.append(hold_pose(mech, frame, axis=axis, base_pose={carrier: angle}, start=start))
        start = held[-1].inputs
    names = list(held[0].inputs)
    splines = {j: scipy.interpolate.CubicSpline(angles, [h.inputs[j] for h in held]) for j in names}
    return HoldingTable(carrier, frame, axis, splines, max(h.tilt for h in held))


@dataclass(frozen=True)
class IsolationPoint:
    """One frequency of the isolation chart.

    Attributes:
        frequency: Hz. bandwidth: the servos' (Hz).
        ratio: the body's residual tilt amplitude over the carrier's.
        theory: |1 - H(jw)| of the ideal linear servo.
        energy_drift: the simulation's energy-balance drift, relative.
    """

    frequency: float
    bandwidth: float
    ratio: float
    theory: float
    energy_drift: float


def servo_theory(frequency: float, bandwidth: float, damping: float = 0.7) -> float:
    """|1 - H(jw)| of a second-order servo with rate feed-forward: the fraction of a command it does not follow.

    Args:
        frequency: Hz.
        bandwidth: the servo's natural frequency (Hz).
        damping: its damping ratio.

    Returns:
        The fraction.
    """
    w, wb = 2 * np.pi * frequency, 2 * np.pi * bandwidth
    return float(w**2 / abs(wb**2 - w**2 + 2j * damping * wb * w))


def isolation_point(
    mech: Mechanism,
    table: HoldingTable,
    amplitude: float,
    frequency: float,
    bandwidth: float,
    damping: float = 0.7,
    periods: int = 3,
    rtol: float = 1e-7,
) -> IsolationPoint:
    """Simulate the carrier at one frequency with the drives as servos; the body's residual tilt.

    Args:
        mech: the mechanism on a moving base.
        table: its holding inputs (`holding_table`, over at least the amplitude).
        amplitude: the carrier's angle amplitude A (rad).
        frequency: the carrier's frequency (Hz, > 0).
        bandwidth: the servos' bandwidth (Hz, > 0).
        damping: the servos' damping ratio.
        periods: carrier periods simulated (>= 2; the first is left out of the fit).
        rtol: the integrator's relative tolerance.

    Returns:
        The `IsolationPoint`.

    Raises:
        InvalidArgument: a frequency not > 0, fewer than 2 periods.
    """
    if not (np.isfinite(frequency) and frequency > 0) or periods < 2:
        raise InvalidArgument("frequency/periods", (frequency, periods), "need a frequency > 0 Hz and >= 2 periods")
    w, k = 2 * np.pi * frequency, BASE_JOINTS.index(table.carrier)

    def base(t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        pos, rate, acc = np.zeros(6), np.zeros(6), np.zeros(6)
        pos[k], rate[k], acc[k] = (
            amplitude * np.sin(w * t),
            amplitude * w * np.cos(w * t),
            -amplitude * w * w * np.sin(w * t),
        )
        return pos, rate, acc

    def command(joint: str):
        return lambda t: table.command(amplitude * np.sin(w * t), amplitude * w * np.cos(w * t))[joint]

    servos = [PositionServo.with_bandwidth(mech, j, command(j), 2 * np.pi * bandwidth, damping) for j in table.splines]
    start = mech.assembly({**dict.fromkeys(BASE_JOINTS, 0.0), **{j: c[0] for j, c in table.command(0.0, 0.0).items()}})
    result = mech.simulate(
        periods / frequency,
        inputs=base,
        input_names=BASE_JOINTS,
        forces=servos,
        q0=start.q,
        dynamics="kkt",
        rtol=rtol,
        atol=rtol * 1e-2,
        max_step=0.02 / max(frequency, bandwidth),
        reactions=False,
    )
    t, tilt = result.t, _tilts(mech, table, result.motion.q)
    keep = t >= 1.0 / frequency
    basis = np.stack([np.sin(w * t[keep]), np.cos(w * t[keep]), np.ones(keep.sum())], axis=1)
    fit = np.linalg.lstsq(basis, tilt[keep], rcond=None)[0]
    return IsolationPoint(
        frequency,
        bandwidth,
        float(np.hypot(*fit[:2])) / amplitude,
        servo_theory(frequency, bandwidth, damping),
        result.energy_error / max(result.energy_scale, 1e-300),
    )


def _tilts(mech: Mechanism, table: HoldingTable, q: np.ndarray) -> np.ndarray:
    """The body's signed tilt about the carrier's world axis at each sample (rad)."""
    axis = {"base_roll": 0, "base_pitch": 1, "base_yaw": 2}[table.carrier]
    body, world = (np.asarray(x, dtype=float) for x in table.axis)
    data, fid = mech.model.createData(), mech.model.getFrameId(table.frame)
    out = np.empty(len(q))
    for i, qi in enumerate(q):
        pin.framesForwardKinematics(mech.model, data, qi)
        turned = np.cross(world, data.oMf[fid].rotation @ body)
        out[i] = np.arcsin(np.clip(turned[axis], -1.0, 1.0))
    return out
