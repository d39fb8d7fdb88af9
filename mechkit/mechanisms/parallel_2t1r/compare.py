"""The 2T1R's inverse dynamics by three methods at one instant and along the paper's motion law.

Pinocchio (closure solve, constrained RNEA with every joint's reaction), SOC (`soc.skcs`, the paper's
SKC order) and classic whole-mechanism virtual work (`soc.classic_torques`, torques only); the
redundantly actuated variant hands the minimum-norm R41 torque of the classic method to the others.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import MechkitError, SingularConfiguration
from mechkit.core import InverseDynamicsResult
from mechkit.mechanism import Mechanism
from mechkit.mechanisms.parallel_2t1r.branch import INPUTS
from mechkit.mechanisms.parallel_2t1r.joint_state import joint_coordinates, joint_positions
from mechkit.mechanisms.parallel_2t1r.motion_law import motion_law, state_at
from mechkit.mechanisms.parallel_2t1r.rates import State
from mechkit.mechanisms.parallel_2t1r.soc import classic_torques, soc_inverse_dynamics

#: Compared quantities: efforts (N m) and the in-plane (determinate) reaction forces (N), world.
QUANTITIES = ("M1", "M2", "M3", "R23_fx", "R23_fz", "R43_fx", "R43_fz")
_EFFORT_JOINT = {"M1": "R11", "M2": "R21", "M3": "R31", "M4": "R41"}
METHODS = ("pinocchio", "soc", "classic")


def pinocchio_motion(
    mech: Mechanism, theta: np.ndarray, rates: np.ndarray, acc: np.ndarray, guess: np.ndarray | dict[str, float] | None
) -> tuple[np.ndarray, ...]:
    """Pinocchio's own motion for the inputs: closure solve from ``guess``, then v and a (SI).

    Args:
        mech: the 2T1R.
        theta: motor angles (3,), rad.
        rates: their rates (3,), rad/s.
        acc: their accelerations (3,), rad/s^2.
        guess: the closure solve's start: a configuration (nq,) or joint -> value.

    Returns:
        (q (nq,), v (nv,), a (nv,)).

    Raises:
        ClosureNotConverged, SingularConfiguration: from `Mechanism.assemble` / `velocities`.
    """
    q = mech.assemble(dict(zip(INPUTS, theta)), guess=guess)
    v = mech.velocities(q, rates, inputs=INPUTS)
    return q, v, mech.accelerations(q, v, acc, inputs=INPUTS)


def pinocchio_inverse_dynamics(
    mech: Mechanism, q: np.ndarray, v: np.ndarray, a: np.ndarray, m4: float | None = None, determinacy: bool = True
) -> InverseDynamicsResult:
    """`Mechanism.inverse_dynamics` of a non-redundant model, with R41's motor torque m4 (N m) as a
    known external torque on link41 when given (the redundant variant with a chosen distribution).

    Args:
        mech: the 2T1R (not the redundant variant).
        q: configuration (nq,).
        v: velocity (nv,).
        a: acceleration (nv,).
        m4: R41's motor torque (N m), or None.
        determinacy: run the determinacy test.

    Returns:
        Efforts and every joint's reaction.
    """
    fext = None
    if m4 is not None:
        fext = [pin.Force.Zero() for _ in range(mech.model.njoints)]
        fext[mech.model.getJointId("R41")] = pin.Force(np.zeros(3), np.array([0.0, m4, 0.0]))
    return mech.inverse_dynamics(q, v, a, fext=fext, determinacy=determinacy)


def evaluate(
    mech: Mechanism, s: State, motion: tuple[np.ndarray, ...] | None, redundant: bool = False, determinacy: bool = False
) -> tuple[dict[str, float], dict[str, str], dict[str, np.ndarray]]:
    """Every method at one instant: values named "<method>:<quantity>", failures by method, and the
    determinacy flags (6,) of Pinocchio's R13, R23, R43 reactions (empty without ``determinacy``).

    Quantities: M1..M3 (M4 when ``redundant``, minimum-norm by classic virtual work and handed to
    the others), R23/R43 fx, fz (SOC, Pinocchio), R13 fx, fz (Pinocchio: the five-bar's compound
    hinge, inside SKC1 for SOC) and each method's condition number ("<method>:cond"). A method that
    raises a `MechkitError` (e.g. `SingularConfiguration`) gives no values and its message.

    Args:
        mech: the 2T1R.
        s: the analytic state (for SOC and classic virtual work).
        motion: Pinocchio's (q, v, a), or None to skip Pinocchio.
        redundant: R41 driven too, minimum-norm torques handed to SOC and Pinocchio.
        determinacy: run the core's determinacy rank test (and get Pinocchio's condition number).

    Returns:
        (values by "<method>:<quantity>" (N m, N), the failures' messages by method, the determinacy flags (6,) by
            joint).
    """
    p = mech.params
    out: dict[str, float] = {}
    failed: dict[str, str] = {}
    flags: dict[str, np.ndarray] = {}
    m4 = None
    try:
        efforts, cond = classic_torques(p, s, INPUTS + (("R41",) if redundant else ()))
        out |= {f"classic:{k}": efforts[j] for k, j in _EFFORT_JOINT.items() if j in efforts}
        out["classic:cond"] = cond
        m4 = efforts.get("R41")
    except MechkitError as err:
        failed["classic"] = str(err)
    runs = [("soc", lambda: soc_inverse_dynamics(p, s, m4))]
    if motion is not None:
        runs.append(("pinocchio", lambda: pinocchio_inverse_dynamics(mech, *motion, m4, determinacy)))
    for method, run in runs:
        if redundant and m4 is None:
            failed[method] = "no R41 torque: the minimum-norm distribution failed"
            continue
        try:
            result = run()
        except MechkitError as err:
            failed[method] = str(err)
            continue
        wrenches = {j: getattr(w, "wrench", w) for j, w in result.reactions.items()}
        out |= {f"{method}:{k}": result.efforts[j] for k, j in _EFFORT_JOINT.items() if j in result.efforts}
        for joint in ("R13", "R23", "R43"):
            if joint in wrenches:
                out[f"{method}:{joint}_fx"], out[f"{method}:{joint}_fz"] = wrenches[joint][[0, 2]]
        if method == "soc":
            out["soc:cond"] = max(result.condition.values())
        else:
            out["pinocchio:cond"] = result.condition
            if determinacy:
                flags = {j: result.reactions[j].determinate for j in ("R13", "R23", "R43")}
                out |= {f"pinocchio:{j}_inplane_determinate": float(f[0] and f[2]) for j, f in flags.items()}
    return out, failed, flags


@dataclass(frozen=True)
class Comparison:
    """`QUANTITIES` (n, 7) by each method along a motion (classic: NaN for the reactions it does not
    give), the Pinocchio-vs-analytic joint error (n,) rad, and the determinacy flags (6,) of the
    Pinocchio reactions at R23 and R43 (first sample)."""

    times: np.ndarray
    values: dict[str, np.ndarray]
    kinematics_error: np.ndarray
    determinate: dict[str, np.ndarray]

    def relative_error(self, method: str) -> np.ndarray:
        """Max |method - Pinocchio| / max |Pinocchio| per quantity (7,) (NaN where not given).

        Args:
            method: "soc" or "classic".

        Returns:
            (7,) relative errors (-).
        """
        ref = self.values["pinocchio"]
        return np.max(np.abs(self.values[method] - ref), axis=0) / np.max(np.abs(ref), axis=0)


def compare_along(mech: Mechanism, times: np.ndarray, redundant: bool = False) -> Comparison:
    """Pinocchio (closure solve + constrained RNEA), SOC and classic virtual work along the motion law.

    Pinocchio's motion is its own: `assemble` from a Taylor step of its previous sample (the first
    from the analytic state), `velocities`, `accelerations`; the analytic state seeds only the first
    guess and is compared joint by joint. ``redundant``: R41 driven too, torques distributed by
    minimum norm (`classic_torques`), the same M4 handed to SOC and Pinocchio.

    Args:
        mech: the 2T1R.
        times: times of the motion law, s.
        redundant: R41 driven too.

    Returns:
        The comparison: per time and method, the values; the kinematic error; Pinocchio's determinacy flags.

    Raises:
        SingularConfiguration: a sample is singular for one of the methods (e.g. t = 0).
    """
    p = mech.params
    rows: dict[str, list] = {m: [] for m in METHODS}
    kin_err = []
    q = v = a = None
    flags: dict[str, np.ndarray] = {}
    previous = 0.0
    for t in np.asarray(times, dtype=float):
        theta, rates, acc = motion_law(t)
        s = state_at(p, theta, rates, acc)
        coords = joint_coordinates(p, s)
        dt = t - previous
        guess = joint_positions(p, s) if q is None else q + v * dt + 0.5 * a * dt * dt
        previous = t
        q, v, a = pinocchio_motion(mech, theta, rates, acc, guess)
        kin_err.append(max(abs(np.angle(np.exp(1j * (q[mech.q_index(j)] - c[0])))) for j, c in coords.items()))
        values, failed, determinate = evaluate(mech, s, (q, v, a), redundant, determinacy=not flags)
        if failed:
            method, why = next(iter(failed.items()))
            raise SingularConfiguration(np.inf, f"t = {t} s, {method}: {why}")
        flags = flags or determinate
        for m in METHODS:
            rows[m].append([values.get(f"{m}:{k}", np.nan) for k in QUANTITIES])
    return Comparison(
        np.asarray(times, dtype=float), {m: np.array(r) for m, r in rows.items()}, np.array(kin_err), flags
    )
