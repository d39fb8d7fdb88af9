"""The assembly re-sought inside the joints' limits (`mechkit.core.inside_limits`), on field files whose start
closes the loops outside them."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

import mechkit
from mechkit import core
from mechkit.core.inside_limits import seek_inside_limits
from tests.tests_support import FIXTURES

GEPETTO = FIXTURES / "field" / "gepetto"
STRANDBEEST = FIXTURES / "drake" / "strandbeest" / "StrandbeestConstraints.urdf.xacro"


def _newton_from_start(m: mechkit.Mechanism) -> tuple[np.ndarray, core.InputSplit, tuple[str, ...]]:
    """The home assembly by Newton from the file's start (no continuation), the split of its given joints,
    and the joints it leaves outside their limits."""
    given = m.spec.home(m.params)
    q0 = m.neutral()
    for joint, value in given.items():
        core.set_joint_value(m.model, q0, m.joint_id(joint), value)
    split = m.closure_model.split(tuple(given))
    out = core.assemble(m.closure_model, m.closure_data, q0, split)
    q, outside = core.wrap_into_limits(m.model, out.q)
    return q, split, outside


def _bounded_violation(m: mechkit.Mechanism, q: np.ndarray) -> float:
    """Largest distance of a bounded one-coordinate joint outside its range (0 inside)."""
    lo, hi = m.model.lowerPositionLimit, m.model.upperPositionLimit
    worst = 0.0
    for j in range(1, m.model.njoints):
        joint = m.model.joints[j]
        i = joint.idx_q
        if joint.nq == 1 and -1e10 < lo[i] < hi[i] < 1e10:
            worst = max(worst, lo[i] - q[i], q[i] - hi[i])
    return worst


@pytest.mark.parametrize(
    ("path", "options"),
    [
        (STRANDBEEST, {"fix": ["crossbar"]}),
        (GEPETTO / "robot_delta" / "robot.urdf", {}),
        (GEPETTO / "battobot_6d" / "robot.urdf", {}),
    ],
    ids=["strandbeest", "robot_delta", "battobot_6d"],
)
def test_an_assembly_outside_the_limits_is_found_again_inside_them(path, options):
    m = mechkit.load(path, **options)
    q_out, split, outside = _newton_from_start(m)
    assert outside, "the file's start must close the loops outside the limits for this test to mean anything"
    found = seek_inside_limits(m.closure_model, m.closure_data, q_out, split, tol=core.CLOSURE_TOL)
    assert found is not None
    assert np.linalg.norm(m.closure_residual(found.q)) <= core.CLOSURE_TOL
    assert _bounded_violation(m, found.q) <= 1e-9
    given = [int(v) for v in split.input_v]
    dv = pin.difference(m.model, q_out, found.q)
    assert np.max(np.abs(dv[given]), initial=0.0) == 0.0  # the given joints stay at their values


def test_no_assembly_inside_the_limits_returns_none():
    m = mechkit.load(GEPETTO / "true_talos_2_legs" / "talos_full_v2.urdf")
    q_out, split, outside = _newton_from_start(m)
    assert {"leg_left_shin_joint", "leg_right_shin_joint"} <= set(outside)  # 200 random starts find none inside
    assert seek_inside_limits(m.closure_model, m.closure_data, q_out, split, tol=core.CLOSURE_TOL) is None
