"""Planar Newton-Euler inverse dynamics of a pin-jointed linkage (numpy only).

Per link: Newton and Euler in the plane, solved at once for every pin force and every actuator
torque of a statically determinate linkage. Conventions (plane x-z, axes and planar moments along
-y) are those of `mechkit.validation.planar_motion`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import InvalidParameters, SingularConfiguration
from mechkit.validation.planar_motion import LinkageState
from mechkit.validation.soc import RANK_TOL

__all__ = ["GRAVITY", "PlanarDynamics", "newton_euler"]

GRAVITY = np.array([0.0, 0.0, -9.81])
"""Default gravity, m/s^2, world (z up)."""


@dataclass(frozen=True)
class PlanarDynamics:
    """Newton-Euler inverse dynamics of a planar linkage.

    Attributes:
        efforts: actuated joint -> motor torque about -y, N m (parent on child).
        reactions: joint -> world wrench (6,) [fx, fy, fz, mx, my, mz] (N, N m) that the parent
            side exerts on the child side at the pin; my = -effort for a driven pin, else 0.
        condition: condition number of the Newton-Euler system.
    """

    efforts: dict[str, float]
    reactions: dict[str, np.ndarray]
    condition: float


def newton_euler(state: LinkageState, gravity: np.ndarray = GRAVITY) -> PlanarDynamics:
    """Per-link planar Newton-Euler: every pin force and every actuator torque.

    Per link: m a_c = m g + sum of pin forces on it; I alpha = sum of their moments about the COM
    + motor torques on it (planar, counter-clockwise = about -y). The linkage must be statically
    determinate in the plane (3 equations per link = 2 per pin + 1 per actuator).

    Args:
        state: the linkage's motion.
        gravity: (3,) m/s^2, world, in the x-z plane.

    Returns:
        Efforts and world reaction wrenches, see :class:`PlanarDynamics`.

    Raises:
        InvalidParameters: gravity out of the plane, or a linkage that is not statically determinate.
        SingularConfiguration: the Newton-Euler system is singular.
    """
    gravity = np.asarray(gravity, dtype=float)
    if gravity.shape != (3,) or gravity[1] != 0.0 or not np.all(np.isfinite(gravity)):
        raise InvalidParameters("gravity", gravity, "must be a finite (3,) vector in the x-z plane")
    links = list(state.links.values())
    row = {link.name: 3 * i for i, link in enumerate(links)}
    actuated = [j.name for j in state.joints if j.actuated]
    n_unknowns = 2 * len(state.joints) + len(actuated)
    if n_unknowns != 3 * len(links):
        why = f"{n_unknowns} unknown pin forces and torques for {3 * len(links)} planar equations"
        raise InvalidParameters("state.joints", [j.name for j in state.joints], why)
    a = np.zeros((n_unknowns, n_unknowns))
    for k, joint in enumerate(state.joints):
        for side, sign in ((joint.parent, -1.0), (joint.child, 1.0)):
            if side is None:
                continue
            r = joint.point - state.links[side].com
            i = row[side]
            a[i : i + 2, 2 * k : 2 * k + 2] += sign * np.eye(2)
            a[i + 2, 2 * k : 2 * k + 2] += sign * np.array([-r[1], r[0]])  # planar r x F
            if joint.actuated:
                a[i + 2, 2 * len(state.joints) + actuated.index(joint.name)] += sign
    b = np.zeros(n_unknowns)
    for link in links:
        i = row[link.name]
        b[i : i + 2] = link.bar.mass * (link.com_acceleration - gravity[[0, 2]])
        b[i + 2] = link.bar.inertia_planar * link.alpha
    sv = np.linalg.svd(a, compute_uv=False)
    if sv[-1] <= RANK_TOL * sv[0]:
        cond = np.inf if sv[-1] == 0.0 else float(sv[0] / sv[-1])
        raise SingularConfiguration(cond, "planar Newton-Euler system")
    x = np.linalg.solve(a, b)
    efforts = {name: float(x[2 * len(state.joints) + i]) for i, name in enumerate(actuated)}
    reactions = {}
    for k, joint in enumerate(state.joints):
        force = x[2 * k : 2 * k + 2]
        moment = -efforts[joint.name] if joint.actuated else 0.0  # motor torque about -y
        reactions[joint.name] = np.array([force[0], 0.0, force[1], 0.0, moment, 0.0])
    return PlanarDynamics(efforts, reactions, float(sv[0] / sv[-1]))
