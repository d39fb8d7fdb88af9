"""The engine gimbal's study of the failure atlas: digits its resultant forward kinematics loses.

Along a line of strokes through the equal-stroke diagonal, where roots of the resultant become
double, the degree-8 eliminant's roots and those of the paper's degree-16 form (whose four-fold roots
at +-i cost digits) are compared with the polished resultant.
"""

from __future__ import annotations

import numpy as np

from mechkit.base.exceptions import MechkitError
from mechkit.catalog.contract import FailureCase, FailureStudy
from mechkit.mechanism import Mechanism
from mechkit.mechanisms.rocket_gimbal import resultant as res
from mechkit.mechanisms.rocket_gimbal.params import geometry

STUDY = "root_loss"
#: Stroke of servo B (m) along the line; servo A is this plus the condition.
BASE_STROKE = 0.05
#: A root counts as real when its imaginary part is below this fraction of (1 + |root|).
REAL_TOL = 1e-7


def root_loss(mech: Mechanism, quick: bool = True) -> list[FailureCase]:
    """Pose error (rad) of the eliminant's and the degree-16 form's roots against the polished resultant.

    Args:
        mech: an engine gimbal (`mechkit.load("rocket_gimbal")`).
        quick: 4 stroke differences (else 8).

    Returns:
        One case per polynomial and stroke difference dlA - dlB (m), the condition.
    """
    geo = geometry(mech.params)
    cases = []
    offsets = [1e-2, 1e-4, 1e-6, 0.0] if quick else [1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-8, 0.0]
    for off in offsets:
        stroke = np.array([BASE_STROKE + off, BASE_STROKE])
        try:
            eqs = res.half_angle_equations(geo, stroke)
            exact = res.pick_in_range(res.fk_resultant(geo, stroke))
        except MechkitError as e:
            cases.append(
                FailureCase(STUDY, "resultant + polish (reference)", off, float("nan"), type(e).__name__, str(e)[:160])
            )
            continue
        for label, poly in (
            ("degree-8 eliminant roots", res.sylvester_resultant(eqs)),
            ("degree-16 form roots", res.degree16_polynomial(eqs)),
        ):
            roots = poly.roots()
            real = roots[np.abs(roots.imag) <= REAL_TOL * (1 + np.abs(roots))].real
            if real.size == 0:
                cases.append(
                    FailureCase(
                        STUDY, label, off, float("nan"), "root lost", "no real root passed the 1e-7 imaginary-part test"
                    )
                )
                continue
            cases.append(FailureCase(STUDY, label, off, float(np.min(np.abs(2 * np.arctan(real) - exact.alpha))), "ok"))
    return cases


FAILURE_STUDIES = (
    FailureStudy(
        STUDY, root_loss, condition="stroke difference dlA - dlB (m)", error="alpha error vs polished resultant (rad)"
    ),
)
