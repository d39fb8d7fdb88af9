"""Constrained forward and inverse dynamics of the core: two methods each, identities, failures."""

from __future__ import annotations

import sysconfig
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from conftest import support_balance_error

import mechkit
from mechkit.base.exceptions import SingularConfiguration

CALIBRATION = ["four_bar", "five_bar"]


def _moving_state(m, rate=1.3, acc=-0.7):
    q = m.home_q
    n = len(m.actuated)
    v = m.velocities(q, rate * np.ones(n))
    a = m.accelerations(q, v, acc * np.ones(n))
    return q, v, a


@pytest.mark.parametrize("name", CALIBRATION)
@pytest.mark.parametrize("rows", ["planar", "spatial"])
def test_kkt_and_proximal_agree(name, rows, load_cached):
    m = load_cached(name, rows=rows)
    q, v, _ = _moving_state(m)
    tau = np.linspace(0.05, -0.04, m.model.nv)
    prox = m.forward_dynamics(q, v, tau, "proximal")
    kkt = m.forward_dynamics(q, v, tau, "kkt")
    assert np.max(np.abs(prox.a - kkt.a)) < 1e-9 * max(1.0, np.max(np.abs(kkt.a)))
    assert np.max(np.abs(prox.constraint_force - kkt.constraint_force)) < 1e-9 * max(
        1.0, np.max(np.abs(kkt.constraint_force))
    )
    # both satisfy the acceleration-level closure
    J, gamma = m.closure_jacobian(q), m.closure_drift(q, v)
    assert np.max(np.abs(J @ kkt.a + gamma)) < 1e-9
    assert np.max(np.abs(J @ prox.a + gamma)) < 1e-9


@pytest.mark.parametrize("name", CALIBRATION)
def test_inverse_then_forward_returns_the_acceleration(name, load_cached):
    m = load_cached(name)
    q, v, a = _moving_state(m)
    inv = m.inverse_dynamics(q, v, a)
    tau = np.zeros(m.model.nv)
    for joint, effort in inv.efforts.items():
        tau[m.v_index(joint)] = effort
    for method in ("kkt", "proximal"):
        back = m.forward_dynamics(q, v, tau, method).a
        assert np.max(np.abs(back - a)) < 1e-9 * max(1.0, np.max(np.abs(a)))


@pytest.mark.parametrize("name", CALIBRATION)
@pytest.mark.parametrize("rows", ["planar", "spatial"])
def test_supports_balance_gravity_and_inertia(name, rows, load_cached):
    """Sum of ground reactions + total weight = total mass x COM acceleration (Newton's second law)."""
    m = load_cached(name, rows=rows)
    assert support_balance_error(m, *_moving_state(m)) < 1e-10


@pytest.mark.parametrize("name", CALIBRATION)
def test_spatial_rows_report_redundancy_and_indeterminate_components(name, load_cached):
    planar, spatial = load_cached(name), load_cached(name, rows="spatial")
    assert planar.mobility().redundant == 0
    assert spatial.mobility().redundant == 3  # 5 spatial rows of a planar pin, 2 independent
    assert spatial.mobility().dof == planar.mobility().dof
    q, v, a = _moving_state(planar)
    r_planar = planar.inverse_dynamics(q, v, a)
    r_spatial = spatial.inverse_dynamics(q, v, a)
    for joint, r in r_spatial.reactions.items():
        # in-plane forces and the moment about the (y) axes are fixed by statics; the rest is not
        np.testing.assert_array_equal(r.determinate, [True, False, True, False, True, False])
        det = r.determinate
        assert np.allclose(r.wrench[det], r_planar.reactions[joint].wrench[det], rtol=0, atol=1e-10)
    for joint, effort in r_planar.efforts.items():
        assert abs(r_spatial.efforts[joint] - effort) < 1e-10


def test_proximal_with_zero_mu_on_redundant_rows_is_an_error_not_nan(load_cached):
    """A planar pin as a 3D point anchor has an exactly zero out-of-plane row: mu = 0 cannot invert it."""
    m = load_cached("four_bar")
    q, v, _ = _moving_state(m)
    with pytest.raises(SingularConfiguration):
        m.forward_dynamics(q, v, np.zeros(m.model.nv), "proximal", mu=0.0, max_iter=1)


def _five_bar_near_stretch(m, delta):
    """Inputs of the five-bar with |B1 B2| = (1 - delta) (dist1 + dist2): distal links nearly collinear."""
    from scipy.optimize import brentq

    p = m.params
    th1 = 2.6
    b1 = p.prox1 * np.array([np.cos(th1), np.sin(th1)])

    def gap(th2):
        b2 = np.array([p.ground + p.prox2 * np.cos(th2), p.prox2 * np.sin(th2)])
        return np.linalg.norm(b2 - b1) - (1 - delta) * (p.dist1 + p.dist2)

    return [th1, brentq(gap, -0.5, 1.5)]


def test_singular_approach_blows_up_then_is_refused(load_cached):
    """Five-bar with its distal links straightening: conditioning and torques grow, then a clear error."""
    m = load_cached("five_bar")
    conds, torques = [], []
    for delta in (1e-2, 1e-4, 1e-6):
        # the spec's guess picks the branch (Newton from it); on the home's branch (continued from home) the
        # conditioning grows the same 100x but the torques 44x (measured), the bound below being 50
        q = m.assemble(_five_bar_near_stretch(m, delta), guess=m.spec.guess(m.params))
        conds.append(m.singularity(q))
        v = m.velocities(q, [0.0, 0.0])
        a = m.accelerations(q, v, [1.0, 0.0])
        torques.append(max(abs(e) for e in m.inverse_dynamics(q, v, a).efforts.values()))
    assert conds[0] < conds[1] < conds[2]
    assert conds[2] / conds[0] > 50  # ~ 1/sqrt(delta)
    assert torques[2] / torques[0] > 50
    # exactly stretched: both distal links along B1B2
    th1, th2 = _five_bar_near_stretch(m, 0.0)
    p = m.params
    b1 = p.prox1 * np.array([np.cos(th1), np.sin(th1)])
    b2 = np.array([p.ground + p.prox2 * np.cos(th2), p.prox2 * np.sin(th2)])
    along = np.arctan2(*(b2 - b1)[::-1])
    q = np.zeros(4)
    q[[m.q_index(j) for j in ("prox1", "dist1", "prox2", "dist2")]] = [th1, along - th1, th2, along + np.pi - th2]
    assert np.max(np.abs(m.closure_residual(q))) < 1e-12
    with pytest.raises(SingularConfiguration):
        m.velocities(q, [1.0, 0.0])
    with pytest.raises(SingularConfiguration):
        m.inverse_dynamics(q, np.zeros(4), np.array([1.0, 0, 0, 0]))


def _example_robot(relative: str) -> str:
    root = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix/share/example-robot-data/robots"
    path = root / relative
    if not path.exists():
        pytest.skip(f"example-robot-data file {relative} not installed")
    return path.read_text()


@pytest.mark.parametrize(
    "robot", ["ur_description/urdf/ur5_robot.urdf", "double_pendulum_description/urdf/double_pendulum.urdf"]
)
def test_reactions_equal_pinocchio_rnea_forces_on_a_third_party_tree(robot):
    urdf = _example_robot(robot)
    joints = [j.get("name") for j in ET.fromstring(urdf).findall("joint") if j.get("type") != "fixed"]
    m = mechkit.from_urdf(urdf, actuated=joints, name=robot)
    rng = np.random.default_rng(7)
    q = pin.randomConfiguration(m.model, -np.ones(m.model.nq), np.ones(m.model.nq))
    v, a = rng.normal(size=m.model.nv), rng.normal(size=m.model.nv)
    got = m.inverse_dynamics(q, v, a)
    data = m.model.createData()
    tau = pin.rnea(m.model, data, q, v, a)
    pin.forwardKinematics(m.model, data, q)
    for i in range(1, m.model.njoints):
        R = data.oMi[i].rotation
        expected = np.concatenate([R @ data.f[i].linear, R @ data.f[i].angular])
        r = got.reactions[m.model.names[i]]
        assert np.max(np.abs(r.wrench - expected)) < 1e-10 * max(1.0, np.max(np.abs(expected)))
        assert r.determinate.all()
    for joint, effort in got.efforts.items():
        assert abs(effort - tau[m.v_index(joint)]) < 1e-10 * max(1.0, abs(effort))


def test_redundant_actuation_flags_efforts_and_offers_least_effort(load_cached):
    """Five-bar with all four joints driven (2 DOF, 4 motors): efforts are a choice, not a fact of statics."""
    five = load_cached("five_bar")
    guess = {j: five.home_q[five.q_index(j)] for j in five.model.names[1:]}
    m = mechkit.from_urdf(five.urdf, actuated=list(guess), name="five_bar_all_driven", guess=guess)
    q, v, a = _moving_state(five)
    results = {d: m.inverse_dynamics(q, v, a, distribution=d) for d in ("min_norm", "min_effort")}
    for res in results.values():
        assert not any(res.efforts_determinate.values())
        tau = np.array([res.efforts[j] for j in m.model.names[1:]])
        back = m.forward_dynamics(q, v, tau, "kkt").a  # either distribution produces the motion
        assert np.max(np.abs(back - a)) < 1e-9 * max(1.0, np.max(np.abs(a)))
    norm = {d: np.linalg.norm(list(r.efforts.values())) for d, r in results.items()}
    assert norm["min_effort"] < norm["min_norm"]
    # the non-redundant five-bar's efforts are fixed by statics
    assert all(five.inverse_dynamics(q, v, a).efforts_determinate.values())
