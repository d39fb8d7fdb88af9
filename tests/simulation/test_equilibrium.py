"""`mechkit.simulation.equilibrium`: the static equilibrium against a simulation that comes to rest there,
with an input held, the reduced force at it against finite differences of the potential, and a pose the
held joints fix."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit import core, forces
from mechkit.base.exceptions import InvalidArgument


def test_released_passive_mechanism_settles_at_the_equilibrium(four_bar):
    """Released at home with a damper on the crank, the four-bar comes to rest where the static
    equilibrium solver says (a stable one), and all its energy went into the damper."""
    damper = forces.JointSprings(four_bar.model, [core.JointSpring("crank", damping=0.05)], "damper")
    run = four_bar.simulate(10.0, forces=[damper], reactions=False)
    eq = four_bar.equilibrium()
    assert eq.stable and eq.residual < 1e-9
    assert np.max(np.abs(run.motion.q[-1] - eq.q)) < 1e-6
    assert run.dissipated[-1] == pytest.approx(-(run.gravity[-1] - run.gravity[0]), rel=1e-6)
    assert run.energy_error <= 1e-6 * run.energy_scale


def test_equilibrium_with_a_held_input(load_cached):
    """The five-bar (two freedoms) with one crank held: the equilibrium keeps it, balances the other
    freedom, and a simulation from there with that crank held stays at rest."""
    five = load_cached("five_bar")
    held = five.actuated[0]
    eq = five.equilibrium({held: 0.4})
    assert eq.q[five.q_index(held)] == pytest.approx(0.4) and eq.residual < 1e-9 and len(eq.stiffness) == 1
    run = five.simulate(0.5, inputs={held: 0.4}, q0=eq.q, reactions=False)
    assert np.max(np.abs(run.motion.q[-1] - eq.q)) < (1e-6 if eq.stable else np.inf)


def _spring_and_potential(m):
    """A spring on the crank (2 N m/rad about 0.3 rad), its equilibrium against gravity, and the potential
    along the one-freedom motion q(theta) (the closure solved at each crank angle near it)."""
    import pinocchio as pin

    spring = forces.JointSprings(m.model, [core.JointSpring("crank", 2.0, 0.3)])
    eq = m.equilibrium(elements=[spring])

    def potential(x):
        q = m.assemble([x], guess=eq.q)
        return pin.computePotentialEnergy(m.model, m.model.createData(), q) + spring.energy(m.model, None, q)

    return eq, potential


def test_the_equilibrium_is_a_minimum_of_the_potential_along_the_motion(four_bar):
    """The potential's central difference along the motion vanishes at the equilibrium and its second
    difference is positive, as the solver reports (stable)."""
    m = four_bar
    eq, potential = _spring_and_potential(m)
    theta, h = eq.q[m.q_index("crank")], 1e-4
    slope = (potential(theta + h) - potential(theta - h)) / (2 * h)
    curvature = (potential(theta + h) - 2 * potential(theta) + potential(theta - h)) / h**2
    assert abs(slope) < 1e-7 and eq.residual < 1e-9
    assert curvature > 0 and eq.stable


def test_the_reported_stiffness_is_the_potentials_curvature(four_bar):
    """The potential's second difference along the motion, divided by |dq/dtheta|^2 (the solver's free
    motion is a unit vector of coordinates), is the reported stiffness."""
    m = four_bar
    eq, potential = _spring_and_potential(m)
    theta, h = eq.q[m.q_index("crank")], 1e-4
    curvature = (potential(theta + h) - 2 * potential(theta) + potential(theta - h)) / h**2
    rate = m.velocities(eq.q, [1.0])
    assert eq.stiffness[0] == pytest.approx(curvature / (rate @ rate), rel=1e-5)


def test_held_joints_that_fix_the_pose_leave_nothing_to_balance(four_bar):
    """The four-bar's crank held: no free motion, the pose is the assembly at that crank angle."""
    eq = four_bar.equilibrium({"crank": 0.7})
    assert eq.iterations == 0 and eq.residual == 0.0 and eq.stiffness.size == 0
    assert np.allclose(eq.q, four_bar.assemble([0.7]), atol=1e-10)


@pytest.mark.parametrize(
    "options, named",
    [
        ({"q0": np.full(3, np.nan)}, "'q0': must be finite"),
        ({"q0": [0.1, 0.2]}, "'q0': expected shape (3,)"),
        ({"max_iter": 0}, "'max_iter': must be >= 1"),
        ({"max_iter": 2.5}, "'max_iter': expected an integer"),
        ({"tol": -1.0}, "'tol': must be > 0"),
        ({"tol": float("nan")}, "'tol': must be finite"),
        ({"elements": [1]}, "'elements[0]': expected a force element"),
        ({"held": {"nope": 0.1}}, "'nope' is not a joint"),
        ({"held": {"crank": float("nan")}}, "held['crank']\": must be finite"),
        ({"held": {"crank": "a"}}, "held['crank']\": expected a real number"),
        ({"held": [0.1]}, "'held': expected a mapping"),
    ],
)
def test_malformed_arguments_are_refused_by_name_before_any_work(four_bar, options, named):
    """A NaN start, no step allowed, a bad tolerance, element or held joint: refused by name (they used to
    reach the solver: a NaN start, an UnboundLocalError at max_iter=0, a ValueError for a held string)."""
    held = options.pop("held", None)
    with pytest.raises(InvalidArgument) as err:
        four_bar.equilibrium(held, **options)
    assert named in str(err.value)


def test_the_description_s_struts_act_by_default():
    """The IFToMM four-bar with a diagonal spring: by default the equilibrium takes the file's
    `<mechkit:strut>` (the rhombus held up at phi = 2.234 rad); without elements the rhombus hangs
    straight down (phi = 3 pi / 2)."""
    from pathlib import Path

    from mechkit import load

    m = load(str(Path(__file__).resolve().parents[1] / "fixtures" / "iftomm" / "spring_four_bar.urdf"))
    crank = m.q_index("crank")
    assert m.equilibrium().q[crank] == pytest.approx(2.2343310190, abs=1e-9)
    assert m.equilibrium(elements=[]).q[crank] == pytest.approx(1.5 * np.pi, abs=1e-9)
