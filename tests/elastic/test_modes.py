"""Natural frequencies: the cantilever's (analytic), and the frame model's for the same lumped masses."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg

import mechkit
from elastic.cantilever import INERTIA, MASS, SECTION, L, cantilever
from elastic.frame_model import FrameModel
from mechkit.base.exceptions import MethodUnavailable
from mechkit.elastic import ElasticModel
from mechkit.elastic.modes import NEAR_MECHANISM

TOL = 1e-6


def test_cantilever_first_frequencies_are_analytic(tmp_path):
    """A massless beam with a tip mass and rotary inertia: bending in each plane is the 2x2 problem
    K = EI/L^3 [[12, -6L], [-6L, 4L^2]] (condensed tip: 3EI/L^3 alone when the inertia vanishes)."""
    e = cantilever(tmp_path)
    modes = e.modes(e.mech.home_q, 6)
    EI = SECTION.E * SECTION.I1
    K = EI / L**3 * np.array([[12.0, -6 * L], [-6 * L, 4 * L**2]])
    bending = np.sqrt(scipy.linalg.eigh(K, np.diag([MASS, INERTIA]), eigvals_only=True)) / (2 * np.pi)
    axial = np.sqrt(SECTION.E * SECTION.A / L / MASS) / (2 * np.pi)
    torsion = np.sqrt(SECTION.G * SECTION.J / L / INERTIA) / (2 * np.pi)
    expected = np.sort(np.concatenate([bending, bending, [axial, torsion]]))
    assert np.allclose(modes.frequencies, expected, rtol=TOL, atol=0)
    phi = modes.shapes[0, 0]  # the first mode: bending, translation normal to the beam
    assert abs(phi[0]) < 1e-9 * np.abs(phi).max()


@pytest.mark.parametrize("name", ["four_bar", "parallel_2t1r", "spherical_2dof"])
def test_frequencies_equal_the_frame_model(name):
    m = mechkit.load(name)
    modes = ElasticModel(m).modes(m.home_q, 6)
    expected = FrameModel(m, m.home_q).frequencies(6)
    assert np.allclose(modes.frequencies, expected, rtol=TOL, atol=0)
    M = modes.shapes.reshape(len(modes.frequencies), -1)
    assert np.all(np.isfinite(M)) and modes.frequencies[0] > 1.0


def test_a_mechanism_that_still_moves_has_no_frequencies(tmp_path):
    from mechkit.base.exceptions import SingularConfiguration

    five = mechkit.load("five_bar", actuated=["prox1"])  # one of two freedoms locked: the five-bar moves
    with pytest.raises(SingularConfiguration):
        ElasticModel(five).modes(five.home_q, 3)


def test_sweep_metrics_of_the_elastic_model():
    """The sweep's elastic metrics: the first frequency is the modes', the mass follows the tubes when the
    rods' masses are the tubes'."""
    from mechkit.sweep.specific import available

    metrics = available("tetra_3rr3uru")
    m = mechkit.load("tetra_3rr3uru", rod_masses="tubes")
    f1 = metrics["first_frequency"].fn(m, None)["first_frequency"]
    assert f1 == pytest.approx(ElasticModel(m).modes(m.home_q, 1).frequencies[0], rel=1e-12)
    heavier = mechkit.load("tetra_3rr3uru", rod_masses="tubes", tube_outer=0.03)
    assert metrics["mass"].fn(heavier, None)["mass"] > metrics["mass"].fn(m, None)["mass"]
    s = metrics["stiffness"].fn(m, None)
    assert set(s) == {f"stiffness.{d}" for d in ("x", "y", "z", "rx", "ry", "rz")} and min(s.values()) > 0


def test_deployable_frequencies_equal_the_frame_model_above_its_near_mechanism():
    """Deployed, the locked truss is nearly mobile (passive condition 1.8e5): its first two modes live in
    the near-null space of the frame model's stiffness (condition 2e15), where double precision leaves
    the frame model 2e-3 and 3e-4 off (docs/elastic.md); every mode above them agrees to 1e-6."""
    m = mechkit.load("deployable_9rr12uru")
    modes = ElasticModel(m).modes(m.home_q, 8)
    expected = FrameModel(m, m.home_q).frequencies(8)
    assert modes.frequencies[1] < 0.01 < modes.frequencies[2]
    assert np.allclose(modes.frequencies[2:], expected[2:], rtol=TOL, atol=0)


def test_a_spring_loaded_freedom_far_softer_than_the_rest_is_a_near_mechanism_mode(load_cached):
    """The ten-bar's spring-loaded freedom (R5's torsion spring, 4 N m/rad) vibrates at 0.137 of the next
    mode: not labelled; with the spring four times softer its frequency halves (f ~ sqrt(k)) to below 0.1 of
    the next, and it is labelled a near-mechanism mode."""
    m = load_cached("ten_bar")
    modes = ElasticModel(m).modes(m.home_q, 3)
    assert not modes.near_mechanism.any() and modes.frequencies[0] > NEAR_MECHANISM * modes.frequencies[1]
    soft = mechkit.load("ten_bar", spring_stiffness=1.0)
    softer = ElasticModel(soft).modes(soft.home_q, 3)
    assert softer.frequencies[0] == pytest.approx(modes.frequencies[0] / 2, rel=1e-3)
    assert softer.near_mechanism.tolist() == [True, False, False]


def test_a_mechanism_locked_by_the_reduction_keeps_its_beams_and_its_modes(load_cached):
    """The ten-bar with its actuator R1 locked at home by `lock` (a reduced tree without R1) has the modes of
    the whole ten-bar, whose actuators the elastic model locks: its beams used to be dropped in silence (a
    mode of 3e16 Hz from round-off)."""
    m = load_cached("ten_bar")
    reduced = mechkit.load("ten_bar", lock={"R1": float(m.home_q[m.q_index("R1")])})
    whole = ElasticModel(m).modes(m.home_q, 4).frequencies
    locked = ElasticModel(reduced).modes(reduced.home_q, 4).frequencies
    assert np.allclose(locked, whole, rtol=1e-9)


def test_nothing_elastic_is_refused_by_name(load_cached):
    m = load_cached("rocket_gimbal")
    with pytest.raises(MethodUnavailable, match="rocket_gimbal has no <mechkit:beam>.*every body is rigid"):
        ElasticModel(m).modes(m.home_q, 2)
    with pytest.raises(MethodUnavailable, match="<mechkit:beam link="):
        ElasticModel(m).stiffness(m.home_q, "engine")
