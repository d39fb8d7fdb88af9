"""`mechkit.motion.path`: a motion keeps its assembly branch, each sample continued from the previous one.

The four-bar (a crank-rocker: the crank turns fully) has two assemblies per crank angle, the open and the
crossed one. Sampled coarsely (7 samples over one crank turn, 1.05 rad apart), Newton from the previous
sample lands on the other assembly; continued from the previous sample the path stays on its branch,
which two independent facts check: every sample is the one a fine continuation (steps of 5 mrad, each
sample of it continued from the last) reaches, and after a whole crank turn the linkage is back at its
start (a crank-rocker's branch is a closed curve over the crank's turn; the other branch is another one).
"""

from pathlib import Path

import numpy as np
import pytest

import mechkit
from mechkit import core, motion
from mechkit.motion.path import PathKinematics

GRIPPER = Path(__file__).parents[1] / "fixtures" / "field" / "menagerie" / "robotiq_2f85" / "2f85.xml"


def _crank_turn(m, samples: int):
    """A law turning the crank once from its home angle, at 2 pi rad/s, in `samples` samples."""
    t = np.linspace(0.0, 1.0, samples)
    start = float(m.home_q[m.q_index("crank")])
    values, rates = (start + 2 * np.pi * t)[:, None], np.full((samples, 1), 2 * np.pi)
    return motion.from_arrays(m, t, values, rates, np.zeros((samples, 1)), names=["crank"], source="turn")


def test_a_coarse_four_bar_motion_stays_on_its_branch_where_newton_jumps():
    m = mechkit.load("four_bar")
    law = _crank_turn(m, 7)
    q = motion.study(m, law).q
    crank, rocker = m.q_index("crank"), m.q_index("rocker")
    fine = m.home_q
    for k in range(1, len(law.t)):  # the fine continuation: 200 steps between samples, each from the last
        for value in np.linspace(law.values[k - 1, 0], law.values[k, 0], 201)[1:]:
            fine = m.assembly({"crank": value}, reference=fine).q
        assert np.max(np.abs(q[k] - fine)) < 1e-9
        assert np.linalg.norm(m.closure_residual(q[k])) < 1e-10
    turned = q[-1] - q[0]  # after a whole crank turn every joint is back, up to whole turns
    assert np.max(np.abs(turned - 2 * np.pi * np.round(turned / (2 * np.pi)))) < 1e-9
    # the test's teeth: Newton from the previous sample (the path's former solve) takes the other assembly
    split, data, newton = m.closure_model.split(("crank",)), m.closure_model.create_data(), [m.home_q]
    for x in law.values[1:, 0]:
        start = newton[-1].copy()
        start[crank] = x
        newton.append(core.assemble(m.closure_model, data, start, split, tol=1e-12).q)
    assert np.max(np.abs(np.array(newton)[:, rocker] - q[:, rocker])) > 1.0


def test_a_gripper_finger_motion_is_the_api_assembly_continued_from_home():
    """The Robotiq 2F-85's drivers 0 -> 0.75 rad in 5 samples (couplers held at their stop, 0): each
    sample is `Mechanism.assembly` continued from home (the file's branch), every joint in its range."""
    g = mechkit.load(GRIPPER)
    names = ["right_driver_joint", "right_coupler_joint", "left_coupler_joint"]
    t = np.linspace(0.0, 1.0, 5)
    values = np.stack([0.75 * t, 0 * t, 0 * t], axis=1)
    law = motion.from_arrays(g, t, values, np.tile([0.75, 0.0, 0.0], (5, 1)), np.zeros((5, 3)), names=names)
    q = motion.study(g, law).q
    lo, hi = g.model.lowerPositionLimit, g.model.upperPositionLimit
    for k in range(5):
        a = g.assembly(dict(zip(names, values[k])))
        assert a.branch == "continued from the home assembly" and a.outside == ()
        assert np.max(np.abs(q[k] - a.q)) < 1e-9
        assert np.all(q[k] >= lo - 1e-9) and np.all(q[k] <= hi + 1e-9)


def test_a_sample_the_branch_cannot_reach_is_refused_by_name():
    """The four-bar's rocker swings between 1.525 and 2.50 rad: driven by it to 1.5 rad past home, no
    continuation closes, and the sample fails naming the branch."""
    m = mechkit.load("four_bar")
    path = PathKinematics(m, ["rocker"])
    target = np.array([float(m.home_q[m.q_index("rocker")]) + 1.5])
    with pytest.raises(mechkit.ClosureNotConverged, match="the previous sample's branch cannot be followed"):
        path.assemble(m.home_q, m.home_q, target, 1e-12)
