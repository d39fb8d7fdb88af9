"""The five-bar's study of the failure atlas: driven towards the pose where its distal bars are collinear.

There the passive block of the closure Jacobian loses rank. Velocities, forward and inverse dynamics
are compared with the closed form and planar Newton-Euler until the core refuses with
`SingularConfiguration` and, past the pose, the linkage cannot assemble (`ClosureNotConverged`).
"""

from __future__ import annotations

import numpy as np

from mechkit.base.exceptions import MechkitError
from mechkit.catalog.contract import FailureCase, FailureStudy
from mechkit.mechanism import Mechanism
from mechkit.mechanisms.five_bar.closed_form import geometry, motion
from mechkit.validation.planar_newton_euler import newton_euler

STUDY = "singularity"
#: The held proximal angle theta2 (rad), and the input rates (rad/s) and accelerations (rad/s^2).
THETA2, RATES, ACCELERATIONS = 0.3, np.array([0.3, -0.2]), np.array([0.5, 0.4])
#: The URDF joints in the order of the closed form's coordinates.
ORDER = ("prox1", "dist1", "prox2", "dist2")


def _relative(x, ref) -> float:
    return float(np.max(np.abs(np.asarray(x) - ref)) / max(float(np.max(np.abs(ref))), 1e-300))


def inputs_at_gap(mech: Mechanism, gap: float) -> np.ndarray:
    """Proximal angles (rad) at which |B1 B2| = dist1 + dist2 - gap (gap in m), with theta2 = `THETA2`.

    theta1 is found by bisection in (pi/2, pi), where |B1 B2| grows monotonically as B1 swings away
    from B2.

    Args:
        mech: the five-bar.
        gap: how far from collinear the distal bars are (m; negative: past it).

    Returns:
        (theta1, theta2), rad.
    """
    g = geometry(mech.params)
    b2 = np.array([g.ground + g.prox2 * np.cos(THETA2), g.prox2 * np.sin(THETA2)])
    target = g.dist1 + g.dist2 - gap
    lo, hi = np.pi / 2, np.pi
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        d = np.hypot(*(g.prox1 * np.array([np.cos(mid), np.sin(mid)]) - b2))
        lo, hi = (mid, hi) if d < target else (lo, mid)
    return np.array([0.5 * (lo + hi), THETA2])


def singularity(mech: Mechanism, quick: bool = True) -> list[FailureCase]:
    """Every method at gaps (m) from 1e-2 down to 1e-14, at the singular pose (0) and 1 mm past it.

    Args:
        mech: a five-bar (`mechkit.load("five_bar")`).
        quick: 7 gaps down to 1e-14 (else 13).

    Returns:
        The cases: per method and gap, its error or the exception it raised.
    """
    gaps = np.logspace(-2, -14, 7 if quick else 13).tolist() + [0.0, -1e-3]
    cases: list[FailureCase] = []
    q = mech.home_q
    for gap in gaps:
        q = _at_gap(mech, gap, q, cases)
    return cases


def _at_gap(m: Mechanism, gap: float, q_prev: np.ndarray, cases: list[FailureCase]) -> np.ndarray:
    """Cases of every method at one gap (m); returns the assembled q (or q_prev) to start the next gap from."""
    order = [m.v_index(j) for j in ORDER]
    th = inputs_at_gap(m, gap)
    try:
        st = motion(m.params, th, RATES, ACCELERATIONS)
        dyn = newton_euler(st)
    except MechkitError as e:
        st = dyn = None
        cases.append(
            FailureCase(
                STUDY, "closed form + Newton-Euler (reference)", gap, float("nan"), type(e).__name__, str(e)[:160]
            )
        )
    guess = q_prev
    if st is not None:
        guess = np.zeros(m.model.nq)
        guess[order] = st.q
    # error vs the closed form; with no reference (at or past the singular pose) the residual it reached
    case = FailureCase.attempt(
        STUDY,
        "assembly (closure Newton)",
        gap,
        lambda: (
            np.linalg.norm(m.closure_residual(m.assemble(th, guess=guess)))
            if st is None
            else _relative(m.assemble(th, guess=guess)[order], st.q)
        ),
    )
    cases.append(case)
    if case.outcome != "ok":
        return q_prev
    q = m.assemble(th, guess=guess)
    cases.append(FailureCase(STUDY, "passive-block condition number", gap, m.singularity(q), "ok"))
    J = m.closure_jacobian(q)
    if st is None:  # at the singular pose itself: no reference; error = the method's own closure residual
        zero = np.zeros(m.model.nv)
        cases.append(
            FailureCase.attempt(STUDY, "velocities (core)", gap, lambda: np.linalg.norm(J @ m.velocities(q, RATES)))
        )
        for method, label in (("proximal", "forward dynamics, proximal"), ("kkt", "forward dynamics, dense KKT")):
            cases.append(
                FailureCase.attempt(
                    STUDY,
                    label,
                    gap,
                    lambda method=method: np.linalg.norm(J @ m.forward_dynamics(q, zero, zero, method).a),
                )
            )
        return q
    v_ref, a_ref, tau = np.zeros(4), np.zeros(4), np.zeros(4)
    v_ref[order], a_ref[order] = st.qd, st.qdd
    efforts = np.array([dyn.efforts["prox1"], dyn.efforts["prox2"]])
    tau[[m.v_index("prox1"), m.v_index("prox2")]] = efforts
    cases.append(FailureCase.attempt(STUDY, "velocities (core)", gap, lambda: _relative(m.velocities(q, RATES), v_ref)))
    for method, label in (("proximal", "forward dynamics, proximal"), ("kkt", "forward dynamics, dense KKT")):
        cases.append(
            FailureCase.attempt(
                STUDY, label, gap, lambda method=method: _relative(m.forward_dynamics(q, v_ref, tau, method).a, a_ref)
            )
        )
    cases.append(
        FailureCase.attempt(
            STUDY,
            "inverse dynamics (efforts)",
            gap,
            lambda: _relative(
                [m.inverse_dynamics(q, v_ref, a_ref, determinacy=False).efforts[j] for j in ("prox1", "prox2")], efforts
            ),
        )
    )
    return q


FAILURE_STUDIES = (
    FailureStudy(
        STUDY,
        singularity,
        condition="distance to the singular pose: dist1 + dist2 - |B1B2| (m)",
        error="relative error vs closed form (-); condition number for the cond row",
        towards_zero=True,
        note="x = 1e-16: at the singular pose; 1e-17: 1 mm past it",
    ),
)
