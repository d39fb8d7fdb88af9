"""The ladder of N four-bar loops: a large closed-loop model of the benchmarks (URDF built in code).

The ladder (values ours, a test model): two rails of N bars (length `RAIL` m, along +z at q = 0),
the left one at x = 0, the right one at x = `RUNG`; on top of left bar i a rung (length `RUNG` m,
along +x), pinned at its far end to the top of right bar i by a planar revolute cut. Every bar is a
uniform rod of `MASS` kg. Loop i is the four-bar (rung i-1 or the ground, left bar i, rung i, right
bar i): 3N joints, 2N independent rows, N degrees of freedom; q = 0 is assembled (rectangles).

Its forward dynamics for many loops is the core's "lcaba" method (Pinocchio's loop-constrained
articulated-body algorithm: O(n) sweeps where `constraintDynamics` factorises with fill-in).
"""

from __future__ import annotations

from mechkit.base.exceptions import InvalidParameters
from mechkit.loading import from_urdf
from mechkit.mechanism import Mechanism

#: Rail bar and rung lengths (m) and the mass of every bar (kg) of the ladder (ours).
RAIL, RUNG, MASS = 0.2, 0.3, 0.1


def _rod(name: str, length: float, axis: int) -> str:
    """A uniform rod link from its frame origin along +x (axis 0) or +z (axis 2)."""
    c = [0.0, 0.0, 0.0]
    c[axis] = length / 2
    end = MASS * length**2 / 12
    inertia = [end, end, end]
    inertia[axis] = MASS * 1e-6  # thin rod: a small axial inertia keeps the inertia positive definite
    return (
        f'<link name="{name}"><inertial><origin xyz="{c[0]} {c[1]} {c[2]}" rpy="0 0 0"/><mass value="{MASS}"/>'
        f'<inertia ixx="{inertia[0]}" ixy="0" ixz="0" iyy="{inertia[1]}" iyz="0" izz="{inertia[2]}"/></inertial></link>'
    )


def _joint(name: str, parent: str, child: str, xyz: tuple[float, float, float], kind: str = "revolute") -> str:
    axis = (
        '<axis xyz="0 1 0"/><limit effort="1e6" lower="-25" upper="25" velocity="1e3"/>' if kind == "revolute" else ""
    )
    return (
        f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
        f'<origin xyz="{xyz[0]} {xyz[1]} {xyz[2]}" rpy="0 0 0"/>{axis}</joint>'
    )


def ladder_urdf(n: int) -> str:
    """URDF text of the ladder of n four-bar loops, closed by `<mechkit:loop>` cuts.

    Args:
        n: the number of loops (>= 1).

    Returns:
        The URDF text.

    Raises:
        InvalidParameters: n < 1.
    """
    if int(n) != n or n < 1:
        raise InvalidParameters("n", n, "the ladder needs a whole number of loops >= 1")
    parts = ['<robot name="ladder" xmlns:mechkit="https://mechkit.dev/loop">', '<link name="ground"/>']
    for i in range(1, n + 1):
        left_parent, right_parent = ("ground", "ground") if i == 1 else (f"left_{i - 1}", f"right_{i - 1}")
        base = 0.0 if i == 1 else RAIL
        parts += [
            _rod(f"left_{i}", RAIL, 2),
            _rod(f"right_{i}", RAIL, 2),
            _rod(f"rung_{i}", RUNG, 0),
            _joint(f"l{i}", left_parent, f"left_{i}", (0.0, 0.0, base)),
            _joint(f"r{i}", right_parent, f"right_{i}", (RUNG if i == 1 else 0.0, 0.0, base)),
            _joint(f"g{i}", f"left_{i}", f"rung_{i}", (0.0, 0.0, RAIL)),
            f'<link name="rung_{i}_end"/>',
            _joint(f"rung_{i}_end_fixed", f"rung_{i}", f"rung_{i}_end", (RUNG, 0.0, 0.0), "fixed"),
            f'<link name="right_{i}_top"/>',
            _joint(f"right_{i}_top_fixed", f"right_{i}", f"right_{i}_top", (0.0, 0.0, RAIL), "fixed"),
            (
                f'<mechkit:loop name="c{i}" type="revolute" rows="planar" axis="0 1 0" frame_a="rung_{i}_end" '
                f'frame_b="right_{i}_top"/>'
            ),
        ]
    parts.append("</robot>")
    return "\n".join(parts)


def ladder(n: int) -> Mechanism:
    """The ladder of n four-bar loops as a Mechanism, actuated at the left rail's joints, home at q = 0.

    Args:
        n: the number of loops (>= 1).

    Returns:
        The mechanism (n DOF, nv = 3 n).

    Raises:
        InvalidParameters: n < 1.
    """
    return from_urdf(ladder_urdf(n), actuated=[f"l{i}" for i in range(1, n + 1)], name=f"ladder_{n}")
