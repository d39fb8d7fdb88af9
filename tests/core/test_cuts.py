"""Every closure kind on a small spatial test linkage: exact Jacobian and drift, mobility, both forward methods."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg
from conftest import support_balance_error

import mechkit
from mechkit.base.exceptions import MethodUnavailable


def _branch(k: int, axes: list[str]) -> str:
    """A 3-revolute branch from the ground; both branches share their joint origins, so their tips meet at q = 0."""
    parts = []
    parent = "ground"
    origins = ["0 0 0", "0.2 0.05 0.03", "0.15 -0.04 0.06"]
    for i, (axis, origin) in enumerate(zip(axes, origins), start=1):
        link = f"b{k}_l{i}"
        parts.append(f"""
  <link name="{link}"><inertial><origin xyz="0.1 0 0"/><mass value="{0.4 + 0.1 * i}"/>
    <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.004" iyz="0" izz="0.004"/></inertial></link>
  <joint name="b{k}_j{i}" type="revolute"><parent link="{parent}"/><child link="{link}"/>
    <origin xyz="{origin}"/><axis xyz="{axis}"/><limit lower="-9" upper="9" effort="1" velocity="1"/></joint>""")
        parent = link
    parts.append(f"""
  <link name="b{k}_tip"/>
  <joint name="b{k}_tip_fixed" type="fixed"><parent link="{parent}"/><child link="b{k}_tip"/>
    <origin xyz="0.1 0.05 0"/></joint>""")
    return "".join(parts)


def linkage(loop: str) -> str:
    return f"""<?xml version="1.0"?>
<robot name="kinds" xmlns:mechkit="https://mechkit.dev/loop">
  <link name="ground"/>{_branch(1, ["0 0 1", "0 1 0", "1 0 0"])}{_branch(2, ["1 0 0", "0 0 1", "0 1 0"])}
  {loop}
</robot>"""


KINDS = {
    "revolute": ('type="revolute" axis="0 0 1"', 1, True),
    "spherical": ('type="spherical"', 3, True),
    "hooke": ('type="hooke" axis_a="1 0 0" axis_b="0 1 0"', 2, False),
    "weld": ('type="weld"', 0, True),
    "prismatic": ('type="prismatic" axis="1 0 0"', 1, False),
}


def build(kind: str) -> mechkit.Mechanism:
    attrs = KINDS[kind][0]
    loop = f'<mechkit:loop name="cut" {attrs} frame_a="b1_tip" frame_b="b2_tip" rows="spatial"/>'
    return mechkit.from_urdf(linkage(loop), actuated=[], name=kind)


@pytest.mark.parametrize("kind", list(KINDS))
def test_jacobian_and_drift_are_exact_derivatives(kind):
    m = build(kind)
    rng = np.random.default_rng(1)
    h = 1e-6
    for _ in range(3):
        q = rng.uniform(-0.4, 0.4, m.model.nq)  # away from closure: the rows are exact everywhere
        dq, v = rng.normal(size=m.model.nv), rng.normal(size=m.model.nv)
        fd = (m.closure_residual(q + h * dq) - m.closure_residual(q - h * dq)) / (2 * h)
        assert np.max(np.abs(m.closure_jacobian(q) @ dq - fd)) < 1e-7
        fd_gamma = (m.closure_jacobian(q + h * v) @ v - m.closure_jacobian(q - h * v) @ v) / (2 * h)
        assert np.max(np.abs(m.closure_drift(q, v) - fd_gamma)) < 1e-6


@pytest.mark.parametrize("kind", list(KINDS))
def test_mobility_is_six_minus_the_rows(kind):
    m = build(kind)
    rows = {"revolute": 5, "spherical": 3, "hooke": 4, "weld": 6, "prismatic": 5}[kind]
    expected_dof = KINDS[kind][1]
    mob = m.mobility()
    assert mob.rows == rows and mob.redundant == 0 and mob.dof == expected_dof


@pytest.mark.parametrize("kind", list(KINDS))
def test_forward_dynamics_methods_agree_or_say_why_not(kind):
    m = build(kind)
    q = m.home_q
    J = m.closure_jacobian(q)
    null = scipy.linalg.null_space(J)
    v = null @ np.linspace(0.5, 1.0, null.shape[1]) if null.size else np.zeros(m.model.nv)
    tau = np.linspace(-0.2, 0.3, m.model.nv)
    kkt = m.forward_dynamics(q, v, tau, "kkt")
    assert np.max(np.abs(J @ kkt.a + m.closure_drift(q, v))) < 1e-9
    if not KINDS[kind][2]:
        with pytest.raises(MethodUnavailable, match=kind):
            m.forward_dynamics(q, v, tau, "proximal")
        return
    prox = m.forward_dynamics(q, v, tau, "proximal")
    assert np.max(np.abs(prox.a - kkt.a)) < 1e-8 * max(1.0, np.max(np.abs(kkt.a)))
    assert np.max(np.abs(prox.constraint_force - kkt.constraint_force)) < 1e-8 * max(
        1.0, np.max(np.abs(kkt.constraint_force))
    )


@pytest.mark.parametrize("kind", list(KINDS))
def test_reactions_hold_every_body_in_equilibrium(kind):
    """With every joint actuated the statics are determinate; the cut wrench and the tree joints'
    wrenches must balance each branch: sum of ground supports = m a_com - m g."""
    loop = f'<mechkit:loop name="cut" {KINDS[kind][0]} frame_a="b1_tip" frame_b="b2_tip" rows="spatial"/>'
    m = mechkit.from_urdf(linkage(loop), actuated=[f"b{k}_j{i}" for k in (1, 2) for i in (1, 2, 3)], name=kind)
    q = m.home_q
    null = scipy.linalg.null_space(m.closure_jacobian(q))
    v = null @ np.linspace(0.5, 1.0, null.shape[1]) if null.size else np.zeros(m.model.nv)
    a = m.forward_dynamics(q, v, np.zeros(m.model.nv), "kkt").a
    assert support_balance_error(m, q, v, a) < 1e-9
