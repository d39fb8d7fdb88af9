"""A cantilever as a mechanism: one link on locked actuated revolutes, its centre of mass (the tip
mass) a length L from the joint, one beam between (helper of the elastic tests). Two joints at the
root (a massless hub between them): the core's kinematic pass does not take a model of one velocity
coordinate (Pinocchio gives its 6 x 1 Jacobian as a vector)."""

from __future__ import annotations

import mechkit
from mechkit.elastic import ElasticModel, Section

L, MASS, INERTIA = 0.5, 2.0, 1e-3  # m, kg, kg m^2 (about every axis through the tip)
SECTION = Section.tube(0.02, 0.016, 70e9, 26e9, axis1=(0.0, 1.0, 0.0))


def cantilever(tmp_path) -> ElasticModel:
    """The cantilever along x from the origin, revolute axis y, locked."""
    urdf = f"""<robot name="cantilever" xmlns:mechkit="https://mechkit.dev/loop">
  <link name="ground"/>
  <link name="arm"><inertial><origin xyz="{L} 0 0"/><mass value="{MASS}"/>
    <inertia ixx="{INERTIA}" ixy="0" ixz="0" iyy="{INERTIA}" iyz="0" izz="{INERTIA}"/></inertial></link>
  <link name="hub"/>
  <joint name="root" type="revolute"><parent link="ground"/><child link="hub"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="1e6" velocity="10"/></joint>
  <joint name="arm_joint" type="revolute"><parent link="hub"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1e6" velocity="10"/></joint>
  <transmission name="t"><joint name="root"/><joint name="arm_joint"/></transmission>
  <mechkit:home joint="root" value="0"/>
  <mechkit:home joint="arm_joint" value="0"/>
</robot>"""
    path = tmp_path / "cantilever.urdf"
    path.write_text(urdf)
    m = mechkit.load(path)
    return ElasticModel(m).with_section("arm", SECTION)
