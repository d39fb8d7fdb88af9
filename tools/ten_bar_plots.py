"""Ten-bar deployment figures: linkage snapshots, joint angles, motor torques, wall supports, drift.

Writes docs/figures/ten_bar_{poses,angles,torques,supports,drift}.png (one Pinocchio-route
deployment, dt = 5 ms, reactions by constrained RNEA with the Lagrange multipliers overlaid).

Usage: python tools/ten_bar_plots.py [--out docs/figures] [--dt 0.005]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import mechkit
from mechkit.mechanisms.ten_bar import checks as tc
from mechkit.mechanisms.ten_bar import dynamics as td
from mechkit.mechanisms.ten_bar import geometry as geo
from mechkit.mechanisms.ten_bar import limits as tl
from mechkit.mechanisms.ten_bar import params as tp

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


def draw_poses(ax, p, angles: np.ndarray) -> None:
    i1, i3, i5 = (td.JOINT_ORDER.index(j) for j in ("R1", "R3", "R5"))
    for k, shade in zip(np.linspace(0, len(angles) - 1, 4).astype(int), ("0.75", "0.55", "0.35", "0.0")):
        a = angles[k]
        pose = geo.pose(p, a[i1], a[i3], a[i5])
        for _, hinges in LINKS:
            pts = np.array([pose.points[h] for h in hinges])
            ax.plot(pts[:, 0], pts[:, 1], "-o", color=shade, lw=1.2, ms=2.5)
        tip = pose.points["R3"] + p.panel2 * geo.unit(pose.angles["l34"])
        for start, end in ((pose.points["R2"], pose.points["R3"]), (pose.points["R3"], tip)):
            ax.plot(
                [start[0], end[0]],
                [start[1], end[1]],
                color="tab:blue",
                lw=4,
                alpha=0.35 + 0.2 * (shade == "0.0"),
            )
    ax.axvline(0.0, color="k", lw=3)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("z (m)")
    ax.set_title("stowed (light) to deployed (black); panels in blue; wall x = 0")


def finish(fig, ax, path: Path, ylabel: str, legend: dict | None = None) -> None:
    """Time axis, labels, legend, grid; write the figure."""
    ax.set_xlabel("time (s)")
    ax.set_ylabel(ylabel)
    ax.legend(**(legend or {}))
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="docs/figures")
    parser.add_argument(
        "--t-end", type=float, default=None, help="stop early (s); default: the whole deployment"
    )
    parser.add_argument("--dt", type=float, default=0.005)
    args = parser.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    m = mechkit.load("ten_bar")
    p = m.params
    run = td.PinocchioDeployment(m)
    traj = td.deploy(run, m.home_q, args.dt, args.t_end)

    fig, ax = plt.subplots(figsize=(7, 6))
    draw_poses(ax, p, traj.angles)
    fig.tight_layout()
    fig.savefig(out / "ten_bar_poses.png", dpi=110)

    fig, ax = plt.subplots(figsize=(8, 4.5))
    for j in td.JOINT_ORDER:
        ax.plot(
            traj.t,
            np.degrees(traj.angles[:, td.JOINT_ORDER.index(j)]),
            lw=2.2 if j in ("R1", "R3", "R5") else 1,
            label=j + (" (motor)" if j in tp.MOTORS else " (spring)" if j == "R5" else ""),
        )
    finish(fig, ax, out / "ten_bar_angles.png", "joint angle (deg)", {"ncol": 3, "fontsize": 8})

    spring = np.array([run.spring_torque(q, v) for q, v in zip(traj.q, traj.v)])
    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.plot(traj.t, traj.torques[:, 0], label="R1 motor (panel 1 on the wall)")
    ax.plot(traj.t, traj.torques[:, 1], label="R3 motor (panel 2 on panel 1)")
    ax.plot(traj.t, spring, label="R5 spring-damper")
    finish(fig, ax, out / "ten_bar_torques.png", "torque (N m)")

    times, results = tc.reactions_along(m, traj, max(1, len(traj.t) // 100))
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2), sharey=True)
    for ax, pair in zip(axes, ("R1", "R5")):
        for comp, name in ((0, "fx"), (1, "fz")):
            ax.plot(
                times, [r.forces[pair][comp] for r in results["pinocchio"]], label=f"{name} constrained RNEA"
            )
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
    fig.tight_layout()
    fig.savefig(out / "ten_bar_supports.png", dpi=110)

    fig, ax = plt.subplots(figsize=(8, 4.5))
    for label, baumgarte, project in tl.STABILISATIONS:
        d = tl.drift(m, 5.0, 0.02, baumgarte, project)
        ax.semilogy(d.t, np.maximum(d.residual, 1e-17), label=label)
    ax.set_title("first 5 s, RK4 dt = 20 ms")
    finish(fig, ax, out / "ten_bar_drift.png", "closure residual (m)")
    for name in ("poses", "angles", "torques", "supports", "drift"):
        print(f"wrote {out / f'ten_bar_{name}.png'}")


if __name__ == "__main__":
    main()
