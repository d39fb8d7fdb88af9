"""Plots of a motion study (matplotlib, Agg): the driven joints' efforts and chosen joints' reaction
force and moment magnitudes over time, with their axial and radial parts."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from mechkit.base.plotting import pyplot, save_figure
from mechkit.history.result import MotionResult
from mechkit.motion.peaks import load_histories

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: Joints shown when none are chosen: the ones with the largest peak force (at most this many).
DEFAULT_JOINTS = 4
#: A reaction panel turns logarithmic when its peak exceeds the median of what it carries this many times.
LOG_SPAN = 100.0


def busiest_joints(result: MotionResult, count: int = DEFAULT_JOINTS) -> list[str]:
    """The `count` joints with the largest peak force, largest first.

    Args:
        result: the study.
        count: how many joints.

    Returns:
        Joint names.
    """
    force = load_histories(result)["force"]
    peak = np.nan_to_num(np.nanmax(np.where(np.isnan(force), -np.inf, force), axis=0), neginf=-1.0)
    return [result.joints[j] for j in np.argsort(-peak, kind="stable")[:count]]


def figure(result: MotionResult, joints: Sequence[str] | None = None, title: str | None = None) -> Figure:
    """A figure: efforts (top), reaction forces (middle) and moments (bottom) of `joints` over time.

    Args:
        result: the study.
        joints: joints whose reactions are drawn (default: `busiest_joints`); solid |f|, dashed radial part,
            dotted axial part.
        title: the figure's title (default: mechanism and source).

    Returns:
        The matplotlib figure.
    """
    plt = pyplot("motion plots")
    joints = list(joints) if joints else busiest_joints(result)
    for joint in joints:
        result.reaction(joint)  # an unknown joint is a named error
    h = load_histories(result)
    fig, axes = plt.subplots(3, 1, figsize=(10, 9), sharex=True)
    top, mid, bottom = axes
    for k, name in enumerate(result.effort_names):
        label = name if name in result.actuated else f"{name} (passive input)"
        top.plot(result.t, result.efforts[:, k], label=label)
    top.set_ylabel("effort (N m or N)")
    top.set_title(title or f"{result.mechanism}: {result.source}")
    for color, joint in enumerate(joints):
        j = result.joints.index(joint)
        for ax, kind in ((mid, "force"), (bottom, "moment")):
            ax.plot(result.t, h[kind][:, j], color=f"C{color}", label=f"{joint} |{kind[0]}|")
            ax.plot(result.t, h[f"radial_{kind}"][:, j], "--", color=f"C{color}", lw=1, label=f"{joint} radial")
            ax.plot(result.t, h[f"axial_{kind}"][:, j], ":", color=f"C{color}", lw=1, label=f"{joint} axial")
    mid.set_ylabel("reaction force (N)")
    bottom.set_ylabel("reaction moment (N m)")
    for ax, kind in ((mid, "force"), (bottom, "moment")):
        shown = h[kind][:, [result.joints.index(j) for j in joints]]
        top = np.nanmax(shown, initial=0.0)
        carried = shown[shown > 1e-9 * top]  # leave out the joints that carry none of it (round-off)
        if carried.size and top > LOG_SPAN * float(np.median(carried)):
            ax.set_yscale("log")  # a peak (near a singularity) decades above the rest
    bottom.set_xlabel("time t (s)")
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    return fig


def write_plot(
    result: MotionResult, path: str | Path, joints: Sequence[str] | None = None, title: str | None = None, dpi: int = 90
) -> Path:
    """Draw `figure` and write it (format from the suffix: .png, .svg, .pdf); atomic.

    Args:
        result: the study.
        path: the file.
        joints: as `figure`.
        title: as `figure`.
        dpi: resolution of a raster format.

    Returns:
        The path written.
    """
    return save_figure(figure(result, joints, title), path, dpi=dpi, tight=False)
