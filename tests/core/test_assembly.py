"""Closing loops from far away (`mechkit.core.assembly`): the far phase closes what the exact rows'
Newton solve does not, and no closure ends with a cut's frames half a turn apart."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from mechkit import core, sources
from mechkit.base.exceptions import ClosureNotConverged
from mechkit.core.assembly import RESTARTS, _far_starts, _solve_rows, flip, from_far
from mechkit.sources.urdf import build_model

GEPETTO = Path(__file__).resolve().parent.parent / "fixtures" / "field" / "gepetto"


def _ball_welded_to_the_ground() -> core.ClosureModel:
    """A body on a ball joint, welded to the ground at the identity: closed only at q = identity."""
    model = pin.Model()
    ball = model.addJoint(0, pin.JointModelSpherical(), pin.SE3.Identity(), "ball")
    model.appendBodyToJoint(ball, pin.Inertia.FromBox(1.0, 0.2, 0.1, 0.05), pin.SE3.Identity())
    model.addFrame(pin.Frame("ground_frame", 0, pin.SE3.Identity(), pin.FrameType.OP_FRAME))
    model.addFrame(pin.Frame("body_frame", ball, pin.SE3.Identity(), pin.FrameType.OP_FRAME))
    return core.ClosureModel(model, [core.LoopClosure("weld", "weld", "ground_frame", "body_frame")])


def test_a_half_turn_satisfies_the_rows_but_not_the_closure():
    """The weld's dot-product rows vanish at a half turn about x; Newton from near it lands there, and
    `assemble` sees the flip and closes the weld for real."""
    cm = _ball_welded_to_the_ground()
    cd = cm.create_data()
    q0 = pin.neutral(cm.model)
    core.set_joint_value(cm.model, q0, 1, np.array([np.pi - 0.05, 0.02, 0.0]))
    split = cm.split(())
    trapped = _solve_rows(cm, cd, q0, split, tol=1e-12, max_iter=60, method="newton", jacobian_at_trials=True)
    assert np.linalg.norm(core.closure_residual(cm, cd, trapped.q)) < 1e-12
    assert flip(cm, cd.pin) == pytest.approx(2.0 * np.sqrt(2.0), rel=1e-6)  # two axes reversed: |2 e_y|, |2 e_z|
    closed = core.assemble(cm, cd, q0, split)
    assert np.linalg.norm(core.joint_value(cm.model, closed.q, 1)) < 1e-9 and flip(cm, cd.pin) < 1e-9


def test_far_starts_of_the_fields_robots_close():
    """Gepetto's cassie_like from its neutral pose: the exact rows' solve alone stalls, the far phase
    brings it near closure, and the whole solve closes it with every weld's frames together."""
    desc = sources.read(GEPETTO / "cassie_like" / "robot.urdf")
    cm = core.ClosureModel(desc.model, desc.closures, desc.couplings, desc.actuated)
    cd = cm.create_data()
    q0, split = pin.neutral(cm.model), cm.split(())
    with pytest.raises(ClosureNotConverged):
        _solve_rows(cm, cd, q0, split, tol=1e-12, max_iter=60, method="newton", jacobian_at_trials=True)
    near = from_far(cm, cd, q0, split)
    assert np.linalg.norm(core.closure_residual(cm, cd, near)) < 1e-6
    closed = core.assemble(cm, cd, q0, split)
    assert closed.residual < 1e-12 and flip(cm, cd.pin) < 1e-9


def test_a_linkage_written_flat_restarts_from_perturbed_starts():
    """URDF+'s six-bar, written flat with its loop open by 0.3 m along the links: the far residual is
    stationary there (no step reduces it, so the far phase alone cannot move), the seeded restarts close
    it, every weld's frames together, and the closed pose is the same on every call (deterministic)."""
    desc = sources.read(GEPETTO.parent / "urdf_plus" / "six_bar.urdf")
    cm = core.ClosureModel(build_model(desc.urdf), desc.closures, desc.couplings, desc.actuated)
    cd = cm.create_data()
    q0, split = pin.neutral(cm.model), cm.split(())
    assert np.linalg.norm(core.closure_residual(cm, cd, q0)) == pytest.approx(0.3, rel=1e-12)
    assert np.linalg.norm(core.closure_residual(cm, cd, from_far(cm, cd, q0, split))) == pytest.approx(0.3, rel=1e-9)
    starts = _far_starts(cm, cd, q0, split)
    assert len(starts) == 1 + RESTARTS and all(
        np.array_equal(a, b) for a, b in zip(starts, _far_starts(cm, cd, q0, split))
    )
    closed = core.assemble(cm, cd, q0, split)
    assert closed.residual < 1e-12 and flip(cm, cd.pin) < 1e-9
    np.testing.assert_array_equal(core.assemble(cm, cd, q0, split).q, closed.q)


def test_a_start_that_is_not_stationary_is_not_perturbed():
    """cassie_like's neutral pose is far but not stationary: the far phase starts from it alone."""
    desc = sources.read(GEPETTO / "cassie_like" / "robot.urdf")
    cm = core.ClosureModel(desc.model, desc.closures, desc.couplings, desc.actuated)
    q0 = pin.neutral(cm.model)
    assert len(_far_starts(cm, cm.create_data(), q0, cm.split(()))) == 1


def test_a_loop_that_cannot_close_is_named_with_its_gap():
    """A ball joint cannot move its body's frame 0.1 m onto a ground frame: the refusal names the loop and
    its gap (the norm of its position rows)."""
    model = pin.Model()
    ball = model.addJoint(0, pin.JointModelSpherical(), pin.SE3.Identity(), "ball")
    model.appendBodyToJoint(ball, pin.Inertia.FromBox(1.0, 0.2, 0.1, 0.05), pin.SE3.Identity())
    model.addFrame(pin.Frame("ground_frame", 0, pin.SE3(np.eye(3), np.array([0.1, 0.0, 0.0])), pin.FrameType.OP_FRAME))
    model.addFrame(pin.Frame("body_frame", ball, pin.SE3.Identity(), pin.FrameType.OP_FRAME))
    cm = core.ClosureModel(model, [core.LoopClosure("out_of_reach", "weld", "ground_frame", "body_frame")])
    with pytest.raises(ClosureNotConverged, match="widest gap: loop 'out_of_reach' by 1.000e-01"):
        core.assemble(cm, cm.create_data(), pin.neutral(model), cm.split(()))
