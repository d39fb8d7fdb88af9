"""`mechkit.forces.described`: the dampers, friction, limits and motor envelopes a URDF or MJCF file declares."""

from __future__ import annotations

import pytest

import mechkit
from mechkit import forces
from mechkit.base.exceptions import MalformedDescription

LIMIT = '<limit effort="1e6" lower="-25.0" upper="25.0" velocity="1e3"/>'
#: The full-turn crank's and coupler's (no stop: xacro/four_bar.urdf.xacro).
FULL_TURN = '<limit effort="1e6" lower="-1000000000.0" upper="1000000000.0" velocity="1e3"/>'


def test_a_file_declares_dampers_friction_and_limits(four_bar):
    urdf = four_bar.urdf.replace(
        FULL_TURN,
        '<limit effort="7" lower="-2" upper="2.5" velocity="3"/><dynamics damping="0.05" friction="0.02"/>',
        1,
    )
    d = forces.described.from_urdf(urdf, four_bar.model, ("crank",))
    first = next(iter(d.limits))
    assert d.limits[first] == (-2.0, 2.5) and d.dampers == {first: 0.05} and d.friction == {first: 0.02}
    assert d.motors == {"crank": (7.0, 3.0)} if first == "crank" else d.motors == {"crank": (1e6, 1e3)}
    names = [e.name for e in d.elements(four_bar.model)]
    assert names == ["joint dampers", "joint friction"]


def test_mjcf_frictionloss_and_ranges(tmp_path):
    pytest.importorskip("mujoco")
    from mechkit.export.mjcf import to_mjcf

    m = mechkit.load("four_bar")
    text = to_mjcf(m).replace(
        'ref="0.6" range="-1000000000.0 1000000000.0"', 'ref="0.6" range="-1 2" frictionloss="0.03"', 1
    )
    path = tmp_path / "fb.xml"
    path.write_text(text)
    d = forces.read_described(path, None, m.model)
    assert d.friction == {"crank": 0.03} and d.limits["crank"] == (-1.0, 2.0)


@pytest.mark.parametrize("dynamics", ['<dynamics damping="soft"/>', '<dynamics friction="inf"/>'])
def test_a_value_that_is_not_a_finite_number_names_its_joint(four_bar, dynamics):
    urdf = four_bar.urdf.replace(LIMIT, LIMIT + dynamics, 1)
    with pytest.raises(MalformedDescription, match="URDF joint"):
        forces.described.from_urdf(urdf, four_bar.model)


def test_the_registered_limits_are_wide_and_nothing_else_is_declared(four_bar):
    """The registered four-bar: +-1e9 rad on its full-turn crank and coupler (no stop), +-25 rad on its rocker,
    its crank's envelope (1e6 N m, 1e3 rad/s), no dampers, no friction, hence no element; without a
    description nothing at all."""
    d = forces.read_described(None, four_bar.urdf, four_bar.model, tuple(four_bar.actuated))
    assert d.limits == {"crank": (-1e9, 1e9), "coupler": (-1e9, 1e9), "rocker": (-25.0, 25.0)}
    assert d.motors == {"crank": (1e6, 1e3)} and not d.dampers and not d.friction
    assert d.elements(four_bar.model) == []
    assert forces.read_described(None, None, four_bar.model) == forces.Described()
