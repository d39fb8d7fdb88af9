"""Structure from the topology: the Kutzbach count, planar / spherical loops and their minimal rows, idle
freedoms."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import mechkit
from mechkit.catalog.registry import names
from mechkit.report import report

FIXTURES = Path(__file__).resolve().parent.parent / "fixtures"


@pytest.mark.parametrize("name", names())
def test_kutzbach_count_of_the_topology_matches_the_declared_count(name, load_cached):
    """The declared counts are modified Gruebler-Kutzbach counts M = Kutzbach + v: v = 0 for seven
    mechanisms; the deployable 9RR-12URU declares 7 with v = 1, an overconstraint its paper finds by
    screw theory at the symmetric configuration (no topology shows it). The numerical rank agrees."""
    m = load_cached(name)
    overconstraint = m.mobility().redundant  # every registered loop is closed with its minimal rows
    assert all(lp.rows == lp.motion_dim - lp.cut_freedoms for lp in m.structure.loops)
    expected_v = 1 if name == "deployable_9rr12uru" else 0
    assert overconstraint == expected_v
    assert m.structure.kutzbach + expected_v == m.spec.gruebler_dof
    assert report(m)["dof_gruebler"] == m.structure.kutzbach


def _without_rows(urdf: str) -> str:
    return re.sub(r' rows="[a-z]+"', "", urdf)


@pytest.mark.parametrize(
    "name, kind",
    [
        ("four_bar", "planar"),
        ("ten_bar", "planar"),
        ("parallel_2t1r", "planar"),
        ("spherical_2dof", "spherical"),
        ("tetra_3rr3uru", "spatial"),
    ],
)
def test_undeclared_rows_are_the_minimal_rows_the_mechanism_declares(name, kind, load_cached, tmp_path):
    """Strip the rows of a registered mechanism's loops: the detection picks what its author chose, and
    the mechanism is the same (mobility and closure rows)."""
    ref = load_cached(name)
    path = tmp_path / f"{name}.urdf"
    path.write_text(_without_rows(ref.urdf))
    m = mechkit.load(
        path,
        actuated=ref.actuated,
        home={j: ref.home_q[ref.q_index(j)] for j in ref.actuated},
        guess=ref.joint_values(ref.home_q),
    )
    assert {lp.kind for lp in m.structure.loops} == {kind}
    assert [c.rows for c in m.closures] == [c.rows for c in ref.closures]
    assert all(lp.chosen == "detected" for lp in m.structure.loops)
    assert m.closure_model.kernel.size == ref.closure_model.kernel.size and m.mobility().dof == ref.mobility().dof
    assert np.max(np.abs(m.closure_jacobian(ref.home_q) - ref.closure_jacobian(ref.home_q))) < 1e-12
    forced = mechkit.load(path, actuated=ref.actuated, guess=ref.joint_values(ref.home_q), rows="spatial")
    assert all(lp.chosen == "forced" and lp.rows == lp.full_rows for lp in forced.structure.loops)
    assert forced.mobility().dof == ref.mobility().dof
    assert (
        forced.mobility().redundant
        == forced.closure_model.kernel.size - m.closure_model.kernel.size + m.mobility().redundant
    )


def test_spherical_rows_of_a_spherical_loop_avoid_position_rows(load_cached, tmp_path):
    ref = load_cached("spherical_2dof")
    path = tmp_path / "s.urdf"
    path.write_text(_without_rows(ref.urdf))
    r = report(mechkit.load(path, actuated=ref.actuated, guess=ref.joint_values(ref.home_q)))
    assert [(lp["kind"], lp["rows"], lp["full_rows"]) for lp in r["loops"]] == [("spherical", 2, 5)] * 2
    assert r["rows_avoided"] == 6 and r["dof_gruebler"] == 2 and r["dof"] == 2


def test_idle_rod_spins_are_found_and_move_nothing_else():
    """The leg's two push rods spin about their own axes (ball joint at each end): two idle freedoms.
    Check the definition: a null-space velocity that turns rod1 about its axis moves no other body. (The
    file writes each top ball as three revolutes: Gepetto's reading merges them into a ball joint.)"""
    m = mechkit.load(FIXTURES / "leg.urdf")
    r = report(m)
    assert r["idle"] == {"rod1": 1, "rod2": 1} and r["dof"] == 4 and r["dof_gruebler"] == 4
    assert m.model.joints[m.model.getJointId("rod1_top_z")].shortname() == "JointModelSpherical"
    v = np.zeros(m.model.nv)
    v[m.v_index("rod1_top_z") + 2] = 1.0  # rod1 is vertical at q = 0: its spin is its ball's rotation about z
    assert np.max(np.abs(m.closure_jacobian(m.home_q) @ v)) < 1e-15
    data = m.model.createData()
    pin.computeJointJacobians(m.model, data, m.home_q)
    rod = m.model.getJointId("rod1_top_z")
    for j in range(1, m.model.njoints):
        twist = pin.getJointJacobian(m.model, data, j, pin.ReferenceFrame.WORLD) @ v
        if j == rod:
            # a unit spin about the vertical line x = 0.06, y = 0.05 (rod1): world-origin velocity -w x p
            assert np.allclose(twist, [0.05, -0.06, 0, 0, 0, 1], atol=1e-15)
        elif m.model.inertias[j].mass > 0:
            assert np.max(np.abs(twist)) < 1e-15, m.model.names[j]


def test_no_idle_freedom_in_the_registered_mechanisms(load_cached):
    for name in ("four_bar", "rocket_gimbal", "spherical_2dof"):
        assert report(load_cached(name))["idle"] == {}
