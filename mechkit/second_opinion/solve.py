"""Per-SKC solve by virtual work with the numpy SOC solver (`mechkit.validation.soc`), in solve order.

Each SKC's virtual coordinates are its equilibrium rows: row (b, k) is a virtual translation of body b
along world axis k (k < 3) or a virtual rotation of b about world axis k - 3 through b's origin, so
the virtual work of a wrench [f, m] at point p on b is f_k, or (m + (p - o_b) x f)_(k-3). A joint's
site Jacobian is its child side's minus its parent side's (the reaction acts + on the child, - on the
parent). Unknowns: the SKC's reaction components (released sites, with the joint's wrench directions
as basis) and efforts (actuators); everything solved by earlier SKCs enters as a known external load.
Blocks that do not fix their unknowns get the minimum-norm solution and report which values are free.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from mechkit.second_opinion.decomposition import SKC
from mechkit.second_opinion.instant import Instant
from mechkit.second_opinion.structure_graph import Structure
from mechkit.validation.soc import BodyLoad, SKCInstant, WrenchSite, solve_soc


@dataclass
class Opinion:
    """The second opinion at one instant.

    Attributes:
        efforts: actuated joint -> effort (N m or N).
        reactions: joint -> (6,) wrench parent side on child side, world, at the joint point
            (a tree joint's includes its effort along its axis, as constrained RNEA reports it).
        free_efforts: actuated joint -> True when its SKC does not fix it (redundant actuation).
        free: joint -> (6,) bool, world components its SKCs do not fix (redundant constraints).
        consistency: SKC index -> relative residual of its virtual-work equations.
    """

    efforts: dict[str, float] = field(default_factory=dict)
    reactions: dict[str, np.ndarray] = field(default_factory=dict)
    free_efforts: dict[str, bool] = field(default_factory=dict)
    free: dict[str, np.ndarray] = field(default_factory=dict)
    consistency: dict[int, float] = field(default_factory=dict)


@dataclass(frozen=True)
class Plan:
    """What one SKC's solve needs besides the instant, worked out once.

    Attributes:
        name: "SKC<i>" (1-based, solve order).
        heads, axes: (n,) its rows: a rigid motion of the subtree of body ``heads[j]`` along (axis
            < 3) or about (axis >= 3) world axis ``axes[j] % 3``.
        bodies: (body id, (n,) bool rows that move it) for every body its rows move.
        joints: joint -> (rows moving its child side, rows moving its parent side), for its released,
            actuated and known joints.
        parts: released joint -> indices of its components solved here.
        actuators: joints whose effort is solved here.
        known: joints (solved, at least in part, by earlier SKCs) whose wrench does work here.
    """

    name: str
    heads: np.ndarray
    axes: np.ndarray
    bodies: tuple[tuple[int, np.ndarray], ...]
    joints: dict[str, tuple[np.ndarray, np.ndarray]]
    parts: dict[str, list[int]]
    actuators: tuple[str, ...]
    known: tuple[str, ...]


def plan(skcs: Sequence[SKC], structure: Structure, loaded: Sequence[str] = ()) -> list[Plan]:
    """What each SKC's solve needs, in solve order.

    Args:
        skcs: the SKCs in solve order.
        structure: the structure graph.
        loaded: joints (springs, dampers) that transmit a known wrench from the start.

    Returns:
        One plan per SKC.
    """
    chains = {b: structure.chain(b) for b in structure.bodies}
    chains[0] = []
    out = []
    solved: set[str] = set(loaded)
    for i, skc in enumerate(skcs):
        heads = np.array([k for k, _ in skc.rows], dtype=int)
        axes = np.array([axis for _, axis in skc.rows], dtype=int)
        masks = {b: np.isin(heads, chain) for b, chain in chains.items()}
        parts: dict[str, list[int]] = {}
        for name, k in skc.unknowns:
            if k >= 0:
                parts.setdefault(name, []).append(k)
        known = tuple(
            j.name for j in structure.joints if j.name in solved and (masks[j.child] != masks[j.parent]).any()
        )
        joints = {
            name: (masks[structure.joint(name).child], masks[structure.joint(name).parent])
            for name in (*parts, *skc.actuators, *known)
        }
        bodies = tuple((b, masks[b]) for b in structure.bodies if masks[b].any())
        out.append(Plan(f"SKC{i + 1}", heads, axes, bodies, joints, parts, skc.actuators, known))
        solved.update(parts, skc.actuators)
    return out


def _site_jacobian(p: Plan, origins: np.ndarray, moved: np.ndarray, point: np.ndarray) -> np.ndarray:
    """(6, n) virtual displacement of ``point`` (rows 0-2) and rotation of its body (rows 3-5) per row,
    ``moved`` marking the rows that carry it; ``origins`` (n, 3) the origin of each row's head body."""
    jac = np.zeros((6, len(p.heads)))
    rows = np.flatnonzero(moved)
    jac[p.axes[rows], rows] = 1.0
    turning = rows[p.axes[rows] >= 3]
    d = point - origins[turning]
    unit = np.eye(3)[p.axes[turning] - 3]
    jac[:3, turning] = np.stack(
        [
            unit[:, 1] * d[:, 2] - unit[:, 2] * d[:, 1],
            unit[:, 2] * d[:, 0] - unit[:, 0] * d[:, 2],
            unit[:, 0] * d[:, 1] - unit[:, 1] * d[:, 0],
        ]
    )
    return jac


def skc_instant(p: Plan, structure: Structure, instant: Instant, known: dict[str, np.ndarray]) -> SKCInstant:
    """The SOC solver's view of one SKC at one instant, with the ``known`` joint wrenches as loads.

    Args:
        p: the SKC's plan.
        structure: the structure graph.
        instant: the instant.
        known: joint -> wrench (6,) solved by earlier SKCs (world, at the joint point).

    Returns:
        The SKC at that instant.
    """
    origins = np.array([instant.bodies[k].origin for k in p.heads]).reshape(-1, 3)
    loads = []
    for b, moved in p.bodies:
        m = instant.bodies[b]
        jac = _site_jacobian(p, origins, moved, m.com)
        loads.append(
            BodyLoad(structure.bodies[b], m.mass, m.inertia, m.com_acceleration, m.omega, m.alpha, jac[:3], jac[3:])
        )

    def joint_jacobian(name: str) -> np.ndarray:
        child, parent = p.joints[name]
        point = instant.joints[name].point
        return _site_jacobian(p, origins, child, point) - _site_jacobian(p, origins, parent, point)

    released = [
        WrenchSite(name, joint_jacobian(name), 1.0, basis=instant.joints[name].basis[:, ks])
        for name, ks in p.parts.items()
    ]
    actuators = [(name, joint_jacobian(name).T @ instant.joints[name].effort) for name in p.actuators]
    external = [(known[name], joint_jacobian(name)) for name in p.known]
    return SKCInstant(p.name, len(p.heads), loads, actuators, released, external=external)


def solve_instant(plans: Sequence[Plan], structure: Structure, instant: Instant) -> Opinion:
    """Solve the SKCs in order at one instant (efforts and every joint's reaction).

    Args:
        plans: the SKCs' plans, in solve order.
        structure: the structure graph.
        instant: the instant.

    Returns:
        The second opinion at that instant.
    """
    out = Opinion()
    known: dict[str, np.ndarray] = {name: w.copy() for name, w in instant.passive.items()}
    for i, p in enumerate(plans):
        result = solve_soc([skc_instant(p, structure, instant, known)], instant.gravity, indeterminate=True)
        out.consistency[i] = result.consistency[p.name]
        for name, wrench in result.reactions.items():
            known[name] = known.get(name, np.zeros(6)) + wrench
            out.free[name] = out.free.get(name, np.zeros(6, bool)) | result.free[name]
        for name, effort in result.efforts.items():
            out.efforts[name] = effort
            out.free_efforts[name] = result.free_efforts[name]
            direction = instant.joints[name].effort
            known[name] = known.get(name, np.zeros(6)) + effort * direction
            if out.free_efforts[name]:
                out.free[name] = out.free.get(name, np.zeros(6, bool)) | (np.abs(direction) > 0.0)
    for joint in structure.joints:
        out.reactions[joint.name] = known.get(joint.name, np.zeros(6))
        out.free.setdefault(joint.name, np.zeros(6, bool))
    return out
