"""The ten-bar's deployment figures, drawn from `studies.deployment` (matplotlib on use).

Linkage snapshots, joint angles, motor and spring torques, wall supports (constrained RNEA with the
Lagrange multipliers overlaid) and the drift of each stabilisation: `ten_bar_{poses,angles,torques,
supports,drift}.png` in the folder given (docs/figures when run by `tools/figures.py ten_bar`).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from mechkit.base.plotting import pyplot, save_figure
from mechkit.mechanisms.ten_bar import dynamics as td
from mechkit.mechanisms.ten_bar import geometry as geo
from mechkit.mechanisms.ten_bar import params as tp
from mechkit.mechanisms.ten_bar.studies import DRIFT_STEP, Deployment

#: Each link drawn as the polyline through its hinges.
LINKS = (
    ("l123", ("R1", "R2", "R10", "R2", "R3")),
    ("l34", ("R3", "R4")),
    ("l48", ("R4", "R8")),
    ("l87", ("R8", "R7")),
    ("l56", ("R5", "R6")),
    ("l67", ("R6", "R7")),
    ("l27", ("R2", "R7")),
    ("l79", ("R7", "R9")),
    ("l910", ("R9", "R10")),
)
DPI = 110


def draw_poses(ax: Any, p: tp.TenBarParams, angles: np.ndarray) -> None:
    """Four poses of the deployment, stowed (light) to deployed (black), the panels in blue.

    Args:
        ax: matplotlib axes.
        p: the design.
        angles: (N, 9) joint angles in `dynamics.JOINT_ORDER` (rad).
    """
    i1, i3, i5 = (td.JOINT_ORDER.index(j) for j in ("R1", "R3", "R5"))
    for k, shade in zip(np.linspace(0, len(angles) - 1, 4).astype(int), ("0.75", "0.55", "0.35", "0.0")):
        a = angles[k]
        pose = geo.pose(p, a[i1], a[i3], a[i5])
        for _, hinges in LINKS:
            pts = np.array([pose.points[h] for h in hinges])
            ax.plot(pts[:, 0], pts[:, 1], "-o", color=shade, lw=1.2, ms=2.5)
        tip = pose.points["R3"] + p.panel2 * geo.unit(pose.angles["l34"])
        for start, end in ((pose.points["R2"], pose.points["R3"]), (pose.points["R3"], tip)):
            ax.plot([start[0], end[0]], [start[1], end[1]], color="tab:blue", lw=4, alpha=0.35 + 0.2 * (shade == "0.0"))
    ax.axvline(0.0, color="k", lw=3)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("z (m)")
    ax.set_title("stowed (light) to deployed (black); panels in blue; wall x = 0")


def _over_time(fig: Any, ax: Any, path: Path, ylabel: str, legend: dict | None = None) -> Path:
    """Time axis, labels, legend, grid; write the figure."""
    ax.set_xlabel("time (s)")
    ax.set_ylabel(ylabel)
    ax.legend(**(legend or {}))
    ax.grid(alpha=0.3)
    return save_figure(fig, path, DPI)


def deployment_figures(d: Deployment, folder: Path) -> list[Path]:
    """The five figures of the deployment: poses, angles, torques, supports, drift.

    Args:
        d: the deployment study.
        folder: where the PNGs go.

    Returns:
        The files written.
    """
    plt = pyplot("ten_bar figures")
    traj, out = d.trajectory, []
    fig, ax = plt.subplots(figsize=(7, 6))
    draw_poses(ax, d.params, traj.angles)
    out.append(save_figure(fig, folder / "ten_bar_poses.png", DPI))

    fig, ax = plt.subplots(figsize=(8, 4.5))
    for j in td.JOINT_ORDER:
        ax.plot(
            traj.t,
            np.degrees(traj.angles[:, td.JOINT_ORDER.index(j)]),
            lw=2.2 if j in ("R1", "R3", "R5") else 1,
            label=j + (" (motor)" if j in tp.MOTORS else " (spring)" if j == "R5" else ""),
        )
    out.append(_over_time(fig, ax, folder / "ten_bar_angles.png", "joint angle (deg)", {"ncol": 3, "fontsize": 8}))

    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.plot(traj.t, traj.torques[:, 0], label="R1 motor (panel 1 on the wall)")
    ax.plot(traj.t, traj.torques[:, 1], label="R3 motor (panel 2 on panel 1)")
    ax.plot(traj.t, d.spring, label="R5 spring-damper")
    out.append(_over_time(fig, ax, folder / "ten_bar_torques.png", "torque (N m)"))

    times, results = d.reaction_times, d.reactions
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2), sharey=True)
    for ax, pair in zip(axes, ("R1", "R5")):
        for comp, name in ((0, "fx"), (1, "fz")):
            ax.plot(times, [r.forces[pair][comp] for r in results["pinocchio"]], label=f"{name} constrained RNEA")
            ax.plot(
                times[::5],
                [r.forces[pair][comp] for r in results["lagrange"]][::5],
                "k.",
                ms=4,
                label=f"{name} Lagrange multiplier" if comp == 0 else None,
            )
        ax.set_title(f"wall support {pair} (force of the wall on the link)")
        ax.set_xlabel("time (s)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    axes[0].set_ylabel("force (N)")
    out.append(save_figure(fig, folder / "ten_bar_supports.png", DPI))

    fig, ax = plt.subplots(figsize=(8, 4.5))
    for label, run in d.drift.items():
        ax.semilogy(run.t, np.maximum(run.residual, 1e-17), label=label)
    ax.set_title(f"first 5 s, fixed step dt = {DRIFT_STEP * 1e3:g} ms")
    out.append(_over_time(fig, ax, folder / "ten_bar_drift.png", "closure residual (m)"))
    return out
