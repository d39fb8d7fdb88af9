"""`mechkit.export`: exporting and re-reading (`mechkit.load(path)`) gives the same mechanism, for every
registered one; a Hooke cut has no export.

Same: the same joints, actuators and cut kinds (a planar loop's pin comes back as the point anchor
it is exported as); the same home assembly; closed where ours is closed;
the same constrained forward dynamics there (joints matched by name: a reader may order them
differently). MJCF carries its home assembly (qpos0 = `ref`); the Extended-URDF pair carries the
home inputs (`<mechkit:home>`) but not the assembly branch, so its re-reading is given our home as
the guess."""

from __future__ import annotations

import numpy as np
import pytest

import mechkit
from mechkit.base.exceptions import MethodUnavailable
from mechkit.catalog import registry
from mechkit.export import export_command, to_extended_urdf, to_mjcf


def test_hooke_cut_has_no_export():
    """A Hooke cut has no MJCF equality nor sidecar pair: a clear MethodUnavailable, not a wrong file."""
    urdf = """<robot name="h" xmlns:mechkit="https://mechkit.dev/loop">
      <link name="base"/>
      <link name="arm"><inertial><mass value="1"/>
        <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <joint name="j1" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>
        <limit effort="1" lower="-3" upper="3" velocity="1"/></joint>
      <link name="arm2"><inertial><mass value="1"/>
        <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <joint name="j2" type="revolute"><parent link="arm"/><child link="arm2"/>
        <origin xyz="0.5 0 0"/><axis xyz="0 0 1"/>
        <limit effort="1" lower="-3" upper="3" velocity="1"/></joint>
      <link name="arm_tip"/><joint name="arm_tip_fixed" type="fixed"><parent link="arm2"/><child link="arm_tip"/>
        <origin xyz="0.5 0 0"/></joint>
      <link name="base_tip"/><joint name="base_tip_fixed" type="fixed"><parent link="base"/><child link="base_tip"/>
        <origin xyz="1 0 0"/></joint>
      <mechkit:loop name="U" type="hooke" frame_a="base_tip" frame_b="arm_tip" axis_a="1 0 0" axis_b="0 1 0"/>
    </robot>"""
    m = mechkit.from_urdf(urdf, actuated=["j1"])
    with pytest.raises(MethodUnavailable, match="hooke"):
        to_mjcf(m)
    with pytest.raises(MethodUnavailable, match="hooke"):
        to_extended_urdf(m)


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
