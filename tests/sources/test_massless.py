"""Massless links and rotors (mass 0 with a rotational inertia), which URDF files write and mechkit accepts:
on the slider-crank fixture with its rod made massless (a two-force member), made a rotor, and with a
massless pendulum hung off the crank, inverse dynamics agrees with an independent computation
(Pinocchio's rnea and the closure rows of `description_reference`), and forward dynamics either solves
with the closure rows (finite accelerations equal to the independent null-space solution
a = N (N^T M N)^-1 N^T (tau - g), where N^T M N is regular) or refuses by name: never a NaN. MuJoCo
holds no moving body without mass or inertia: the MJCF export refuses it by name."""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
import scipy.linalg

import mechkit
from mechkit.base.exceptions import MechkitError, MethodUnavailable
from mechkit.core import FORWARD_METHODS
from mechkit.export import to_mjcf
from mechkit.sources import read

from .description_reference import Statics

SLIDER = (Path(__file__).resolve().parents[1] / "fixtures" / "slider_crank.urdf").read_text()
ROD = re.compile(
    r'(<link name="rod_link">\s*<inertial><origin xyz="0.15 0 0"/>)<mass value="0.4"/>(\s*<inertia [^/]*/>)'
)
VARIANTS = {
    "massless rod": ROD.sub(r'\1<mass value="0"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>', SLIDER),
    "rotor rod": ROD.sub(r'\1<mass value="0"/>\2', SLIDER),
    "massless pendulum": SLIDER.replace(
        "</robot>",
        '<link name="tip"/><joint name="tip" type="revolute"><parent '
        'link="crank_link"/><child link="tip"/><origin xyz="0.05 0 0"/><axis xyz="0 -1 0"/>'
        '<limit effort="1" lower="-3" upper="3" velocity="1"/></joint></robot>',
    ),
}


@pytest.fixture(params=list(VARIANTS))
def variant(request, tmp_path):
    path = tmp_path / "slider.urdf"
    path.write_text(VARIANTS[request.param])
    assert VARIANTS[request.param] != SLIDER
    return request.param, path


def _loaded(path: Path):
    """The mechanism, and its description with the tree Pinocchio's URDF parser builds (the reference's)."""
    m = mechkit.load(path)
    return m, dataclasses.replace(read(path), model=pin.buildModelFromXML(path.read_text()), closures=tuple(m.closures))


def test_inverse_dynamics_with_a_massless_subtree_agrees_with_an_independent_computation(variant):
    name, path = variant
    m, desc = _loaded(path)
    inputs = list(m.actuated) + (["tip"] if name == "massless pendulum" else [])
    q = m.home_q
    v = m.velocities(q, [0.7, -0.4][: len(inputs)], inputs)
    a = m.accelerations(q, v, [0.3, 0.8][: len(inputs)], inputs)
    ours = m.inverse_dynamics(q, v, a)
    st = Statics(desc, tuple(inputs[1:]))  # the pendulum's joint held like a motor (it carries nothing)
    A = np.hstack([st.S, st.rows(q)[1].T])
    b = pin.rnea(desc.model, desc.model.createData(), q, v, a)
    x, *_ = np.linalg.lstsq(A, b, rcond=None)
    assert np.linalg.norm(A @ x - b) < 1e-12 * max(1.0, np.linalg.norm(b))
    assert ours.efforts["crank"] == pytest.approx(x[0], abs=1e-10 * max(1.0, abs(x[0])))
    if name == "massless pendulum":
        assert x[1] == pytest.approx(0.0, abs=1e-15)  # nothing to hold on a massless leaf


def test_forward_dynamics_solves_with_the_closure_rows_or_refuses_by_name(variant):
    """At rest under a crank torque: each method's accelerations are finite and the independent ones, or
    the method refuses (a MechkitError). The massless pendulum's acceleration is undetermined (N^T M N
    is singular): every method refuses it; the massless rod's coordinate without inertia is fixed by the
    closure (N^T M N regular): lcaba, KKT and the null-space method solve it (Pinocchio's proximal solver
    returns NaN there and is refused by name); the rotor carries inertia: every method solves it."""
    name, path = variant
    m, desc = _loaded(path)
    q, v = m.home_q, np.zeros(m.model.nv)
    tau = m.generalized_forces({"crank": 0.3})
    data = desc.model.createData()
    M = pin.crba(desc.model, data, q)
    M = np.triu(M) + np.triu(M, 1).T
    N = scipy.linalg.null_space(Statics(desc).rows(q)[1])
    reduced = N.T @ M @ N
    well_posed = np.linalg.eigvalsh(reduced)[0] > 1e-9 * np.max(np.abs(reduced))
    assert well_posed == (name != "massless pendulum")
    solved = {}
    for method in FORWARD_METHODS:
        try:
            a = m.forward_dynamics(q, v, tau, method).a
        except MechkitError:
            continue
        assert np.all(np.isfinite(a)), method
        solved[method] = a
    if not well_posed:
        assert solved == {}
        return
    g = pin.computeGeneralizedGravity(desc.model, data, q)
    expected = N @ np.linalg.solve(reduced, N.T @ (tau - g))
    for method, a in solved.items():
        assert np.max(np.abs(a - expected)) < 1e-8 * max(1.0, np.max(np.abs(expected))), method
    assert {"lcaba", "kkt", "nullspace"} <= set(solved)
    if name == "rotor rod":
        assert set(solved) == set(FORWARD_METHODS)


def test_the_mjcf_export_refuses_a_body_mujoco_cannot_hold(variant):
    _, path = variant
    with pytest.raises(MethodUnavailable, match="MuJoCo needs both above 1e-15 for a moving body"):
        to_mjcf(mechkit.load(path))
