"""`mechkit.simulation.jacobian`: the Jacobian of the simulator's first-order system against central differences
of its right-hand side on random states of the four-bar, the ten-bar and the flyball governor; Radau with it
against RK45 at tight tolerances; where it does not apply, scipy's differences are used."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import mechkit
from mechkit import simulation
from mechkit.simulation.declared import default_forces
from mechkit.simulation.jacobian import SystemJacobian
from mechkit.simulation.state_layout import StateLayout

from .pins import friction

FLYBALL = Path(__file__).resolve().parents[1] / "fixtures" / "iftomm" / "flyball_governor.urdf"


def _system(m):
    elements = default_forces(m, None)
    system = simulation.MechanismSystem(m, elements, simulation.Drives(), "proximal")
    return system, StateLayout(m.model, 1 + len(elements))


def _rhs(system, layout):
    def f(t, y):
        ev = system.evaluate(t, layout.q(y), layout.v(y))
        return layout.derivative(y, ev.a, np.concatenate([[0.0], ev.powers]))

    return f


def _central(f, y, step=1e-6):
    out = np.empty((y.size, y.size))
    for k in range(y.size):
        e = np.zeros(y.size)
        e[k] = step * max(1.0, abs(y[k]))
        out[:, k] = (f(0.0, y + e) - f(0.0, y - e)) / (2 * e[k])
    return out


@pytest.mark.parametrize("name", ["four_bar", "ten_bar", "flyball"])
def test_the_jacobian_is_the_central_difference_of_the_right_hand_side(load_cached, name):
    """Random states near home (q off the manifold by ~0.05 rad, random v and works): the Jacobian equals the
    central differences of dy/dt to 1e-6 of its largest entry (measured 1e-9 on the loops, whose q block is
    itself differenced, and 5e-11 on the flyball); the flyball's spring block is stiff (entries ~1e5)."""
    m = mechkit.load(FLYBALL) if name == "flyball" else load_cached(name)
    system, layout = _system(m)
    jac = SystemJacobian(system, layout).current()
    assert jac is not None
    f = _rhs(system, layout)
    rng = np.random.default_rng(7)
    for _ in range(2):
        q = m.home_q + 0.05 * rng.normal(size=m.model.nq)
        y = layout.pack(q, rng.normal(size=m.model.nv), rng.normal(size=layout.n_work))
        exact, differenced = jac(0.0, y), _central(f, y)
        scale = np.abs(differenced).max()
        assert np.abs(exact - differenced).max() <= 1e-6 * scale
        assert np.abs(exact[m.model.nq :, : m.model.nq]).max() > 1.0  # a block that can be wrong is not zero
    if name == "flyball":
        assert scale > 1e4


def test_pinocchio_s_own_position_derivative_on_a_loop_is_not_used(four_bar):
    """Why the loops' q block is differenced: Pinocchio 4.1's `computeConstraintDynamicsDerivatives` gives
    d a / d q off by more than 1e-2 of its largest entry on the four-bar (the crank's column), while its v and
    tau blocks agree with central differences to 1e-6. If a Pinocchio release fixes it, this fails: then
    take its q block on loops too."""
    system, layout = _system(four_bar)
    jacobian = SystemJacobian(system, layout)
    rng = np.random.default_rng(3)
    q, v, tau = four_bar.home_q.copy(), rng.normal(size=3), rng.normal(size=3)
    _, a_q, a_v, _ = jacobian.dynamics(q, v, tau)
    legacy = jacobian.legacy
    legacy.dynamics(q, v, tau, jacobian.settings)
    pin_q, pin_v = pin.computeConstraintDynamicsDerivatives(
        four_bar.model, legacy.data, legacy.models, legacy.datas, jacobian.settings
    )[:2]
    assert np.abs(pin_q - a_q).max() > 1e-2 * np.abs(a_q).max()
    assert np.abs(pin_v - a_v).max() < 1e-6 * np.abs(a_v).max()


@pytest.mark.parametrize("name, duration", [("four_bar", 0.5), ("flyball", 0.05)])
def test_radau_with_it_follows_rk45(load_cached, name, duration, monkeypatch):
    """Radau at rtol 1e-10 with the Jacobian (called: counted) and RK45 at rtol 1e-11 give the same joint
    trajectory to 1e-7 rad (m) at the end; the four-bar released from home, the flyball's shaft at 2 pi rad/s."""
    m = mechkit.load(FLYBALL) if name == "flyball" else load_cached(name)
    v0 = np.zeros(m.model.nv)
    if name == "flyball":
        v0[m.v_index("shaft")] = 2 * np.pi
    calls = []
    original = SystemJacobian.__call__
    monkeypatch.setattr(SystemJacobian, "__call__", lambda self, t, y: calls.append(t) or original(self, t, y))
    radau = m.simulate(duration, v0=v0, method="Radau", rtol=1e-10, atol=1e-12, limits=None, reactions=False)
    monkeypatch.undo()
    rk45 = m.simulate(duration, v0=v0, rtol=1e-11, atol=1e-13, limits=None, reactions=False)
    assert calls and radau.t[-1] == pytest.approx(duration)
    assert np.max(np.abs(radau.motion.q[-1] - rk45.motion.q[-1])) < 1e-7
    assert np.max(np.abs(rk45.motion.q[-1] - rk45.motion.q[0])) > 1e-2  # it moved


def test_where_it_does_not_apply_scipy_differences_are_used(four_bar):
    """Friction from the reactions, drives, and the near-singular mode: no Jacobian (None)."""
    rubbing = simulation.MechanismSystem(four_bar, [friction(four_bar)], simulation.Drives(), "kkt")
    assert SystemJacobian(rubbing, StateLayout(four_bar.model, 2)).current() is None
    driven = simulation.MechanismSystem(four_bar, [], simulation.Drives(held={"crank": 0.0}), "proximal")
    assert SystemJacobian(driven, StateLayout(four_bar.model, 1)).current() is None
    free = simulation.MechanismSystem(four_bar, [], simulation.Drives(), "proximal")
    assert SystemJacobian(free, StateLayout(four_bar.model, 1), lambda: True).current() is None
    assert SystemJacobian(free, StateLayout(four_bar.model, 1), lambda: False).current() is not None
