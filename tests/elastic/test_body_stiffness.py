"""`mechkit.elastic.body_stiffness`: what physics guarantees of a body's stiffness, over one link softened by
ten decades: compliance positive semi-definite, stiffness finite where nothing holds the body rigidly, and a
softer link never stiffer in any direction (Loewner order of the compliances; K_ii and 1/C_ii never rise).
A link a billion times softer than the rest used to give a stiffness of inf in every direction."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from mechkit.elastic import ElasticModel
from mechkit.elastic.body_stiffness import body_stiffness

#: (mechanism, link softened, body measured)
CASES = [("four_bar", "crank_link", "coupler_link"), ("parallel_2t1r", "link11", "platform")]


@pytest.mark.parametrize("name, link, body", CASES)
def test_a_softer_link_never_stiffens_any_direction(load_cached, name, link, body):
    m = load_cached(name)
    e = ElasticModel(m)
    section = e.data.sections[link]
    previous = None
    for decade in range(11):
        softer = e.with_section(link, dataclasses.replace(section, E=section.E * 10.0**-decade))
        s = softer.stiffness(m.home_q, body)
        C, scale = s.compliance, np.abs(s.compliance).max()
        assert np.all(np.isfinite(C)) and np.linalg.eigvalsh(C).min() >= -1e-12 * scale
        assert s.rigid.shape == (6, 0) and np.all(np.isfinite(s.held)) and np.all(s.held > 0)
        assert np.all(np.isfinite(s.stiffness)) and np.linalg.eigvalsh(s.stiffness).min() > 0
        if previous is not None:
            assert np.linalg.eigvalsh(C - previous.compliance).min() >= -1e-12 * scale, decade
            # K = C^-1 of a C exact to round-off is exact to eps cond(C): no rise beyond that
            lam = np.linalg.eigvalsh(C)
            bound = np.finfo(float).eps * lam.max() / lam.min()
            assert np.all(s.held <= previous.held * (1 + bound)), (decade, s.held / previous.held - 1, bound)
            assert np.all(s.free <= previous.free * (1 + bound)), (decade, s.free / previous.free - 1, bound)
        previous = s


def test_a_direction_held_rigidly_is_infinite_and_said_so_not_a_number():
    """A compliance with a rigid direction (zero in the structure): K is the inverse off it, K_ii infinite only
    for the axes that have a component along it, 1/C_ii infinite only for the axis within it."""
    rng = np.random.default_rng(3)
    A = rng.standard_normal((6, 5))
    A[0] = 0.0  # nothing yields along x
    C = A @ A.T
    s = body_stiffness("b", np.zeros(3), C, C)
    assert s.rigid.shape == (6, 1) and abs(abs(s.rigid[0, 0]) - 1) < 1e-12
    assert s.held[0] == np.inf and np.all(np.isfinite(s.held[1:]))
    assert s.free[0] == np.inf and np.all(np.isfinite(s.free[1:]))
    inner = np.ix_(range(1, 6), range(1, 6))
    assert np.allclose(s.stiffness[inner], np.linalg.inv(C[inner]), rtol=1e-10)


def test_a_compliance_from_round_off_is_clipped_to_positive_semi_definite():
    C = np.diag([1.0, 2.0, 3.0, 4.0, 5.0, 6.0])
    C[0, 1] = C[1, 0] = 1.0000000001  # an eigenvalue of -1e-10
    s = body_stiffness("b", np.zeros(3), C, np.eye(6))
    assert np.linalg.eigvalsh(s.compliance).min() >= 0.0
