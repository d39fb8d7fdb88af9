"""`mechkit.simulation.state_layout`: the integrated vector of a simulation: packed and read back, and off a
vector space (a free-flying body) its position part's rate against the motion Pinocchio integrates."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from mechkit.simulation.state_layout import StateLayout


def test_revolute_joints_pack_q_itself(four_bar):
    m = four_bar
    layout = StateLayout(m.model, 2)
    q, v, w = m.assemble([0.9]), np.array([0.1, -0.2, 0.3]), np.array([4.0, 5.0])
    y = layout.pack(q, v, w)
    assert layout.euclidean and y.size == m.model.nq + m.model.nv + 2
    assert np.array_equal(layout.q(y), q) and np.array_equal(layout.v(y), v) and np.array_equal(layout.works(y), w)
    a, powers = np.array([1.0, 2.0, 3.0]), np.array([-1.0, 0.5])
    assert np.array_equal(layout.derivative(y, a, powers), np.concatenate([v, a, powers]))


def _free_body() -> pin.Model:
    model = pin.Model()
    j = model.addJoint(0, pin.JointModelFreeFlyer(), pin.SE3.Identity(), "base")
    model.appendBodyToJoint(j, pin.Inertia.FromBox(2.0, 0.3, 0.2, 0.1), pin.SE3.Identity())
    return model


def test_a_free_flyers_offset_moves_the_configuration_at_its_velocity():
    """Off a vector space y holds a tangent offset d from a base: packing makes q the base (d = 0); at a
    state with d != 0, a small Euler step of y along `derivative` moves q(y) as integrate(q(y), h v) to
    second order in h."""
    model = _free_body()
    layout = StateLayout(model, 1)
    rng = np.random.default_rng(11)
    q0 = pin.randomConfiguration(model, -np.ones(model.nq), np.ones(model.nq))
    v = rng.normal(size=model.nv)
    y = layout.pack(q0, v, np.zeros(1))
    assert not layout.euclidean and np.array_equal(y[: model.nv], np.zeros(model.nv))
    assert np.allclose(layout.q(y), q0, atol=1e-15)
    y[: model.nv] = rng.normal(size=model.nv) * 0.5  # an offset the integrator has built up
    q = layout.q(y)
    dy = layout.derivative(y, np.zeros(model.nv), np.zeros(1))
    errors = []
    for h in (1e-3, 5e-4):
        moved = layout.q(y + h * dy)
        errors.append(np.max(np.abs(pin.difference(model, pin.integrate(model, q, h * v), moved))))
    assert errors[0] < 1e-5 and errors[1] == pytest.approx(errors[0] / 4, rel=0.05)


def test_file_mechanism_falls_with_its_loops_closed():
    """Cassie (MuJoCo Menagerie: a free-flying pelvis, so the layout off a vector space; loops by equality
    connects) falling for 20 ms: its loops stay closed and its energy balance holds."""
    pytest.importorskip("mujoco")
    from pathlib import Path

    import mechkit

    path = Path(__file__).resolve().parents[1] / "fixtures/field/menagerie/agility_cassie/cassie.xml"
    mech = mechkit.load(path)
    run = mech.simulate(0.02, source=path, reactions=False)
    assert run.residual.max() <= 1e-10
    assert run.energy_error <= 1e-6 * run.energy_scale
