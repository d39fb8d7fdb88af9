"""A two-link arm drawn only by mesh visuals (the STL and OBJ boxes of tests/fixtures/meshes)."""

from __future__ import annotations

import itertools

import numpy as np
from tests_support import FIXTURES

MESHES = FIXTURES / "meshes"  # box.stl, box.obj: 1 x 2 x 1, corner at 0
BOX = np.array(list(itertools.product((0, 1), (0, 2), (0, 1))), dtype=float)
SCALE = np.array([0.1, 0.05, 0.2])
ORIGIN = np.array([0.3, 0.0, 0.1])  # visual origin in its link (m)
INERTIAL = '<inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>'


def arm(first: str, second: str) -> str:
    """Two revolute links, each drawn by one mesh visual."""

    def link(name, filename):
        return (
            f'<link name="{name}">{INERTIAL}<visual><origin xyz="{" ".join(map(str, ORIGIN))}" rpy="0 0 0.4"/>'
            f'<geometry><mesh filename="{filename}" scale="{" ".join(map(str, SCALE))}"/></geometry></visual></link>'
        )

    return (
        f'<robot name="arm"><link name="base"/>{link("a", first)}{link("b", second)}'
        '<joint name="j1" type="revolute"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/>'
        '<limit lower="-3" upper="3" effort="1" velocity="1"/></joint>'
        '<joint name="j2" type="revolute"><parent link="a"/><child link="b"/><origin xyz="0.5 0 0"/>'
        '<axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint></robot>'
    )
