"""Stiffness maps over the workspace: a body's stiffness in each direction over a grid of two inputs
(the others held at their home values), and a plot of them."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mechkit.base.exceptions import ClosureNotConverged, InvalidParameters, SingularConfiguration
from mechkit.base.plotting import pyplot, save_figure
from mechkit.elastic.elastic_model import ElasticModel

DIRECTIONS = ("x", "y", "z", "rx", "ry", "rz")
#: Largest change of any coordinate (rad or m) between neighbouring poses of one assembly branch (ours).
BRANCH_JUMP = 0.1


@dataclass(frozen=True)
class StiffnessMap:
    """A body's stiffness over a grid of two inputs.

    Attributes:
        body: the body's link.
        point: (3,) the point in its frame (m).
        inputs: the two input joints.
        values: their grids ((n1,), (n2,); rad or m).
        held: (n1, n2, 6) K_ii (every other direction held; N/m, N m/rad); nan where the pose does not
            assemble or is singular.
        free: (n1, n2, 6) 1 / C_ii (every other direction free).
    """

    body: str
    point: np.ndarray
    inputs: tuple[str, str]
    values: tuple[np.ndarray, np.ndarray]
    held: np.ndarray
    free: np.ndarray


def stiffness_map(
    elastic: ElasticModel, body: str, inputs: dict[str, np.ndarray], point: np.ndarray | None = None
) -> StiffnessMap:
    """A body's stiffness over the grid of two input joints' values (the other actuators at home).

    The grid is walked breadth first from the cell nearest home, each pose assembled from an accepted
    neighbour's: a pose that does not assemble, is singular or jumps to another assembly branch is left
    out (nan), and so is what lies beyond it.

    Args:
        elastic: the elastic model.
        body: the body's URDF link.
        inputs: two input joints -> their grids of values (rad or m).
        point: (3,) the point in the link's frame (m); default its origin.

    Returns:
        The `StiffnessMap`.

    Raises:
        InvalidParameters: not exactly two inputs.
    """
    if len(inputs) != 2:
        raise InvalidParameters("inputs", list(inputs), "a map takes exactly two input joints")
    mech = elastic.mech
    (j1, v1), (j2, v2) = ((j, np.asarray(v, dtype=float)) for j, v in inputs.items())
    home = mech.joint_values(mech.home_q)
    given = {a: home[a] for a in mech.actuated}
    held = np.full((len(v1), len(v2), 6), np.nan)
    free = np.full_like(held, np.nan)
    poses: dict[tuple[int, int], np.ndarray] = {}
    start = (int(np.argmin(np.abs(v1 - home[j1]))), int(np.argmin(np.abs(v2 - home[j2]))))
    queue, seen = [(start, mech.home_q)], {start}
    while queue:  # breadth first from the cell nearest home, each pose from an accepted neighbour's
        (a, b), guess = queue.pop(0)
        try:
            q = mech.assemble({**given, j1: v1[a], j2: v2[b]}, guess=guess)
            if np.max(np.abs(q - guess)) > BRANCH_JUMP:
                continue  # another assembly branch: not this map's
            s = elastic.stiffness(q, body, point)
        except (ClosureNotConverged, SingularConfiguration):
            continue
        held[a, b], free[a, b] = s.held, s.free
        poses[(a, b)] = q
        for cell in ((a + 1, b), (a - 1, b), (a, b + 1), (a, b - 1)):
            if 0 <= cell[0] < len(v1) and 0 <= cell[1] < len(v2) and cell not in seen:
                seen.add(cell)
                queue.append((cell, q))
    return StiffnessMap(
        body, np.zeros(3) if point is None else np.asarray(point, dtype=float), (j1, j2), (v1, v2), held, free
    )


def plot_map(result: StiffnessMap, direction: str, path: Path) -> Path:
    """A PNG of the map in one direction: K_ii and 1/C_ii side by side (log colour scale).

    Args:
        result: the map.
        direction: one of "x", "y", "z", "rx", "ry", "rz".
        path: the PNG file to write.

    Returns:
        The path written.

    Raises:
        InvalidParameters: an unknown direction.
    """
    if direction not in DIRECTIONS:
        raise InvalidParameters("direction", direction, f"one of {DIRECTIONS}")
    k = DIRECTIONS.index(direction)
    unit = "N/m" if k < 3 else "N m/rad"
    plt = pyplot("stiffness maps")
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    (j1, j2), (v1, v2) = result.inputs, result.values
    for ax, values, title in (
        (axes[0], result.held, "K_ii (others held)"),
        (axes[1], result.free, "1/C_ii (others free)"),
    ):
        image = ax.pcolormesh(np.degrees(v2), np.degrees(v1), np.log10(values[..., k]), shading="auto")
        ax.set_xlabel(f"{j2} (deg)")
        ax.set_ylabel(f"{j1} (deg)")
        ax.set_title(f"{result.body}, {direction}: {title}")
        fig.colorbar(image, ax=ax, label=f"log10 stiffness ({unit})")
    return save_figure(fig, Path(path))
