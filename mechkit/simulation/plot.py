"""The figure of a simulation (matplotlib, Agg): the joints' values, the energy terms with the balance's
drift, and the closure residual over time."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from mechkit.base.plotting import pyplot, save_figure
from mechkit.simulation.result import SimulationResult

#: One-coordinate joints drawn in the top panel (the first ones of the tree).
MAX_JOINTS = 12


def figure(result: SimulationResult, title: str | None = None) -> Any:
    """The simulation's figure: joint values (top), energies and the balance's drift (middle), closure
    residual (bottom).

    Args:
        result: the simulation.
        title: the figure's title (default: the mechanism and the motion's source).

    Returns:
        The matplotlib figure.
    """
    plt = pyplot("simulation plots")
    fig, (top, mid, bottom) = plt.subplots(3, 1, figsize=(10, 9), sharex=True)
    t, motion = result.t, result.motion
    for k, name in enumerate(motion.coordinates[:MAX_JOINTS]):
        top.plot(t, np.degrees(motion.q[:, k]), lw=1.5 if name in motion.effort_names else 1, label=name)
    top.set_ylabel("joint value (deg or m x 57.3)")
    top.legend(fontsize=7, ncol=4)
    T, V = result.kinetic, result.gravity + result.potentials.sum(axis=1)
    for values, label in (
        (T, "kinetic"),
        (V - V[0], "potential (change)"),
        (result.supplied, "supplied"),
        (result.dissipated, "dissipated"),
        (result.balance - result.balance[0], "balance drift"),
    ):
        mid.plot(t, values, label=label)
    mid.set_ylabel("energy (J)")
    mid.legend(fontsize=8)
    bottom.semilogy(t, np.maximum(result.residual, 1e-17))
    bottom.set_ylabel("closure residual (m)")
    bottom.set_xlabel("t (s)")
    fig.suptitle(title or f"{motion.mechanism}: {motion.source}")
    fig.tight_layout()
    return fig


def write_plot(result: SimulationResult, path: str | Path) -> Path:
    """Write `figure(result)` (.png, .svg, .pdf by suffix); atomic.

    Args:
        result: the simulation.
        path: the file to write (its suffix picks the format; none: PNG).

    Returns:
        The path written.
    """
    return save_figure(figure(result), path, dpi=110, tight=False)
