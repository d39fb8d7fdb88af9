"""Exporting and re-reading (`mechkit.load(path)`) gives the same mechanism, for every registered one.

Same: the same joints, actuators and cut kinds (a planar loop's pin comes back as the point anchor
it is exported as); the same home assembly; closed where ours is closed;
the same constrained forward dynamics there (joints matched by name: a reader may order them
differently). MJCF carries its home assembly (qpos0 = `ref`); the Extended-URDF pair carries the
home inputs (`<mechkit:home>`) but not the assembly branch, so its re-reading is given our home as
the guess.
"""

from __future__ import annotations

import numpy as np
import pytest

import mechkit
from mechkit.catalog import registry
from mechkit.export import export_command

pytest.importorskip("mujoco")

FORMATS = {"mjcf": "xml", "extended-urdf": "urdf"}


def _anchor_kind(closure) -> str:
    """A cut's kind as the formats carry it: a pin of a planar loop is one point anchor (a ball joint
    whose in-plane rows are the pin's), so it comes back as a spherical cut with the same rows."""
    return "spherical" if closure.kind == "revolute" and closure.rows == "planar" else closure.kind


def _by_name(m, values: np.ndarray) -> dict[str, float]:
    return {m.model.names[j]: float(values[m.model.idx_vs[j]]) for j in range(1, m.model.njoints)}


def _in_order(m, named: dict[str, float]) -> np.ndarray:
    out = np.zeros(m.model.nv)
    for name, value in named.items():
        out[m.v_index(name)] = value
    return out


@pytest.mark.parametrize("fmt", FORMATS)
@pytest.mark.parametrize("name", registry.names())
def test_export_then_load_gives_the_same_mechanism(name, fmt, load_cached, tmp_path):
    m = load_cached(name)
    path = export_command(m, fmt, tmp_path / f"{name}.{FORMATS[fmt]}")[0]
    guess = _by_name(m, m.home_q) if fmt == "extended-urdf" else None
    r = mechkit.load(path, guess=guess)
    assert sorted(r.model.names) == sorted(m.model.names)
    assert r.actuated == m.actuated
    assert sorted(_anchor_kind(c) for c in r.closures) == sorted(_anchor_kind(c) for c in m.closures)
    # the same home assembly, closed on the re-read model
    home = _in_order(r, _by_name(m, m.home_q))
    np.testing.assert_allclose(r.home_q, home, atol=1e-9)
    assert np.max(np.abs(r.closure_residual(home))) < 1e-12
    assert r.mobility().dof == m.mobility().dof
    # the same constrained dynamics there: at rest under gravity, and under a unit motor effort
    tau = np.zeros(m.model.nv)
    tau[m.v_index(m.actuated[0])] = 1.0
    for effort in (np.zeros(m.model.nv), tau):
        ours = m.forward_dynamics(m.home_q, np.zeros(m.model.nv), effort, "kkt").a
        theirs = r.forward_dynamics(home, np.zeros(r.model.nv), _in_order(r, _by_name(m, effort)), "kkt").a
        scale = max(1.0, float(np.max(np.abs(ours))))
        np.testing.assert_allclose(_in_order(m, _by_name(r, theirs)), ours, atol=1e-8 * scale)
