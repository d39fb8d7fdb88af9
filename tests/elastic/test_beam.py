"""The beam: a cantilever's tip deflection PL^3/3EI and rotation, by the model and by PyNite's own solve."""

from __future__ import annotations

import numpy as np
from Pynite import FEModel3D

from elastic.cantilever import SECTION, L, cantilever
from mechkit.elastic.beam import cantilever_compliance, stiffness


def test_cantilever_tip_deflection_is_pl3_over_3ei(tmp_path):
    e = cantilever(tmp_path)
    P = 100.0
    tip = e.deflection(e.mech.home_q, "arm", np.array([0.0, 0.0, -P, 0.0, 0.0, 0.0]), np.array([L, 0.0, 0.0]))
    EI = SECTION.E * SECTION.I1
    assert np.isclose(tip[2], -P * L**3 / (3 * EI), rtol=1e-12, atol=0)
    assert np.isclose(tip[4], P * L**2 / (2 * EI), rtol=1e-12, atol=0)  # a downward tip load turns the tip about +y
    assert np.isclose(tip[0], 0.0, atol=1e-15)


def test_cantilever_agrees_with_pynites_own_analysis():
    """An oblique cantilever, clamped at one end, loaded at the other: PyNite's supports, loads and
    linear analysis against the compliance of `beam`."""
    start, end = np.zeros(3), np.array([0.3, 0.2, -0.1])
    fe = FEModel3D()
    fe.add_node("a", *start)
    fe.add_node("b", *end)
    fe.add_material("m", SECTION.E, SECTION.G, SECTION.E / (2 * SECTION.G) - 1, 0.0)
    fe.add_section("s", SECTION.A, SECTION.I1, SECTION.I2, SECTION.J)
    fe.add_member("ab", "a", "b", "m", "s")
    fe.def_support("a", True, True, True, True, True, True)
    load = np.array([30.0, -20.0, 50.0, 4.0, -3.0, 2.0])
    for name, value in zip(("FX", "FY", "FZ", "MX", "MY", "MZ"), load):
        fe.add_node_load("b", name, float(value))
    fe.analyze_linear(check_statics=False)
    node = fe.nodes["b"]
    pynite = np.array([getattr(node, d)["Combo 1"] for d in ("DX", "DY", "DZ", "RX", "RY", "RZ")])
    ours = cantilever_compliance(end, start, SECTION) @ load
    assert np.allclose(ours, pynite, rtol=0, atol=1e-9 * np.abs(pynite).max())
    K = stiffness(start, end, SECTION)
    assert np.allclose(K, K.T) and np.linalg.matrix_rank(K) == 6  # six rigid-body motions, no more
