"""`ElasticModel` against an independent finite-element frame model (PyNite members, `frame_model.py`):
reactions under gravity and under a lateral force, body compliances, at 1e-6 relative; the rigid limit."""

from __future__ import annotations

import itertools

import numpy as np
import pinocchio as pin
import pytest

import mechkit
from elastic.frame_model import FrameModel
from mechkit.elastic import ElasticModel, JointElasticity

TOL = 1e-6


def _lateral(m, body: int, force: np.ndarray) -> np.ndarray:
    """(njoints, 6) a world force (N) at a body's centre of mass, as Pinocchio's local external force."""
    data = m.model.createData()
    pin.forwardKinematics(m.model, data, m.home_q)
    local = data.oMi[body].rotation.T @ force
    fext = np.zeros((m.model.njoints, 6))
    fext[body] = np.concatenate([local, np.cross(m.model.inertias[body].lever, local)])
    return fext


def _agreement(r, fe: dict) -> float:
    """Largest reaction difference over the largest reaction (every joint, every component)."""
    scale = max(np.abs(w).max() for w in fe.values())
    return max(np.abs(r.reactions[0, k] - fe[name]).max() for k, name in enumerate(r.joint_names)) / scale


@pytest.fixture(scope="module")
def four_bar():
    return mechkit.load("four_bar", rows="spatial")


def test_four_bar_in_space_out_of_plane_reactions_equal_the_frame_model(four_bar):
    """Gravity alone leaves the out-of-plane components zero by symmetry; a lateral force on the coupler
    loads them: indeterminate when rigid, determinate now, and the frame model's to 1e-6."""
    m, e = four_bar, ElasticModel(four_bar)
    v = np.zeros(m.model.nv)
    fm = FrameModel(m, m.home_q)
    gravity = e.inverse_dynamics(m.home_q, v, v)
    assert _agreement(gravity, fm.reactions(fm.loads())) < TOL
    assert np.abs(gravity.reactions[0][:, [1, 3, 5]]).max() < 1e-9 * np.abs(gravity.reactions).max()
    coupler = e.body("coupler_link")
    force = np.array([0.0, 20.0, 0.0])
    lateral = e.inverse_dynamics(m.home_q, v, v, _lateral(m, coupler, force))
    fe = fm.reactions(fm.loads({coupler: np.concatenate([force, np.zeros(3)])}))
    assert _agreement(lateral, fe) < TOL
    assert not lateral.rigid_determinate.all() and lateral.determinate.all()
    out_of_plane = lateral.reaction("C")[0][[1, 3, 5]]
    assert np.abs(out_of_plane).max() > 1.0  # the cut now carries a real share of the lateral load


def test_rigid_limit(four_bar):
    """As every joint's and drive's stiffness grows, the determinate components stay the rigid inverse
    dynamics' exactly and the others converge to the ideal joints' values; scaling every stiffness
    together changes nothing."""
    m = four_bar
    e = ElasticModel(m)
    v = np.zeros(m.model.nv)
    fext = _lateral(m, e.body("coupler_link"), np.array([5.0, 20.0, -3.0]))
    rigid = m.inverse_dynamics(m.home_q, v, v, fext)
    ideal = e.inverse_dynamics(m.home_q, v, v, fext).reactions[0]
    det = rigid.determinate
    scale = np.abs(ideal).max()
    errors = []
    for k in (1e4, 1e6, 1e8, 1e10):
        soft = e
        for joint in m.closure_model.joint_names:
            soft = soft.with_joint(
                joint, JointElasticity(stiffness=np.full(6, k), drive=k if joint in m.actuated else None)
            )
        r = soft.inverse_dynamics(m.home_q, v, v, fext).reactions[0]
        assert np.abs(r[det] - rigid.reaction_values[det]).max() < 1e-9 * scale
        errors.append(np.abs(r - ideal).max() / scale)
    assert errors[0] > 1e-4 and all(b < a / 5 for a, b in itertools.pairwise(errors)) and errors[-1] < 1e-6
    scaled = ElasticModel(m, e.data.scaled(1e3)).inverse_dynamics(m.home_q, v, v, fext).reactions[0]
    assert np.abs(scaled - ideal).max() < 1e-9 * scale


def test_determinate_four_bar_reactions_do_not_depend_on_the_sections():
    """In its plane (planar rows) the four-bar is statically determinate: its reactions are the rigid
    ones whatever the sections."""
    m = mechkit.load("four_bar")
    e = ElasticModel(m)
    v = np.zeros(m.model.nv)
    rigid = m.inverse_dynamics(m.home_q, v, v).reaction_values
    section = e.data.sections["coupler_link"]
    for factor in (0.1, 10.0):
        other = e.with_section("coupler_link", type(section).tube(0.05 * factor**0.25, 0.0, 2e11, 8e10, (0, -1, 0)))
        r = other.inverse_dynamics(m.home_q, v, v).reactions[0]
        planar = np.ix_(range(len(r)), [0, 2, 4])
        assert np.abs(r[planar] - rigid[planar]).max() < 1e-9 * np.abs(rigid).max()


@pytest.mark.parametrize(
    "name, link",
    [
        ("four_bar", "coupler_link"),
        ("five_bar", "dist1_link"),
        ("parallel_2t1r", "platform"),
        ("spherical_2dof", "platform"),
    ],
)
def test_body_compliance_equals_the_frame_model(name, link):
    m = mechkit.load(name)
    e = ElasticModel(m)
    point = np.array([0.01, -0.02, 0.03])
    C = e.compliance(m.home_q, link, point)
    fm = FrameModel(m, m.home_q)
    Cf = fm.compliance(e.body(link), e.point(m.home_q, link, point))
    assert np.abs(C - Cf).max() < TOL * np.abs(Cf).max()
    s = e.stiffness(m.home_q, link, point)
    assert np.all(s.held >= s.free * (1 - 1e-9))  # holding the other directions never makes it softer
    wrench = np.array([10.0, -5.0, 20.0, 1.0, 0.5, -2.0])
    assert np.allclose(
        e.deflection(m.home_q, link, wrench, point), Cf @ wrench, rtol=0, atol=TOL * np.abs(Cf @ wrench).max()
    )


def test_2t1r_limb_iii_reactions_equal_the_frame_model():
    m = mechkit.load("parallel_2t1r")
    e = ElasticModel(m)
    v = np.zeros(m.model.nv)
    fm = FrameModel(m, m.home_q)
    r = e.inverse_dynamics(m.home_q, v, v)
    fe = fm.reactions(fm.loads())
    assert _agreement(r, fe) < TOL
    assert r.determinate.all()
    for joint in ("R41", "R42", "R43", "R23"):
        assert np.abs(r.reaction(joint)[0] - fe[joint]).max() < TOL * np.abs(fe[joint]).max()


def test_batched_reactions_equal_one_at_a_time(four_bar):
    m, e = four_bar, ElasticModel(four_bar)
    qs = np.array([m.assemble({"crank": x}) for x in (0.3, 0.6, 0.9)])
    v = np.zeros((3, m.model.nv))
    batch = e.inverse_dynamics_batch(qs, v, v)
    for i in range(3):
        one = e.inverse_dynamics(qs[i], v[i], v[i])
        assert np.allclose(batch.reactions[i], one.reactions[0], rtol=0, atol=1e-12 * np.abs(batch.reactions).max())


def test_motion_study_gains_the_compliant_reactions(four_bar):
    """A motion study with reactions="compliant" gives `ElasticModel`'s reactions at its states; the
    components rigid statics fixes are the rigid study's."""
    from mechkit.motion import from_callable, study

    m = four_bar
    law = from_callable(m, lambda t: [0.6 + 0.3 * np.sin(2.0 * t)], np.linspace(0.0, 1.0, 9))
    rigid = study(m, law, determinacy=True)
    compliant = study(m, law, determinacy=True, reactions="compliant")
    direct = ElasticModel(m).inverse_dynamics_batch(compliant.q, compliant.v, compliant.a)
    scale = np.abs(direct.reactions).max()
    assert np.abs(compliant.reactions - direct.reactions).max() < 1e-9 * scale
    assert compliant.determinate.all() and not rigid.determinate.all()
    fixed = rigid.determinate
    assert np.abs(compliant.reactions[fixed] - rigid.reactions[fixed]).max() < 1e-9 * scale
    assert np.allclose(compliant.efforts, rigid.efforts, rtol=1e-9, atol=1e-9 * np.abs(rigid.efforts).max())


def test_joint_and_drive_stiffness_equal_the_frame_model(four_bar):
    """Bearings as 6x6 diagonal stiffness on every joint (their constrained directions) and a drive
    stiffness on the crank: reactions, compliance and frequencies against the frame model's springs."""
    m = four_bar
    e = ElasticModel(m)
    for k, joint in enumerate(m.closure_model.joint_names):
        stiffness = np.array([2e6, 3e6, 4e6, 5e3, 6e3, 7e3]) * (1 + k)
        e = e.with_joint(joint, JointElasticity(stiffness=stiffness, drive=800.0 if joint in m.actuated else None))
    coupler = e.body("coupler_link")
    force = np.array([3.0, 20.0, -2.0])
    v = np.zeros(m.model.nv)
    r = e.inverse_dynamics(m.home_q, v, v, _lateral(m, coupler, force))
    fm = FrameModel(m, m.home_q, e.data)
    assert _agreement(r, fm.reactions(fm.loads({coupler: np.concatenate([force, np.zeros(3)])}))) < TOL
    point = e.point(m.home_q, "rocker_link", [0.1, 0.0, 0.0])
    C = e.compliance(m.home_q, "rocker_link", [0.1, 0.0, 0.0])
    assert np.abs(C - fm.compliance(e.body("rocker_link"), point)).max() < TOL * np.abs(C).max()
    assert np.allclose(e.modes(m.home_q, 4).frequencies, fm.frequencies(4), rtol=TOL, atol=0)


def test_compatible_checks_its_arguments(four_bar):
    from mechkit.base.exceptions import InvalidArgument, InvalidParameters

    e = ElasticModel(four_bar)
    q = four_bar.home_q[None]
    good = {"q": q, "efforts": np.zeros((1, 1)), "reactions": np.zeros((1, 4, 6))}
    for bad in (
        {"efforts": np.zeros((1, 2))},
        {"reactions": np.zeros((1, 3, 6))},
        {"reactions": np.full((1, 4, 6), np.nan)},
    ):
        with pytest.raises(InvalidArgument):
            e.compatible(**{**good, **bad})
    with pytest.raises(InvalidParameters):
        e.compatible(**good, drives=("rocker",))
