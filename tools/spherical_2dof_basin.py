"""Where the forward kinematics of the 2-DOF spherical platform fails: convergence basins.

For a regular pose of the cone scene and a pose 0.4 deg from the forward singularity, starts on
circles of growing radius about the answer; per FK method (the paper's, Newton on eq. 7, the core's
closure solver) the fraction that finds the answer, that lands on another assembly, that fails, and
the mean iteration count. Writes docs/figures/spherical_2dof_basin.png and prints the table.
Usage: python tools/spherical_2dof_basin.py [--directions 24]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from mechkit.base.exceptions import InvalidParameters
from mechkit.loading import load
from mechkit.mechanisms.spherical_2dof import kinematics as kin
from mechkit.mechanisms.spherical_2dof.fk import METHODS, NEAR_SINGULAR, REGULAR, basin_study
from mechkit.mechanisms.spherical_2dof.kinematics import BRANCHES
from mechkit.mechanisms.spherical_2dof.scenes import cone_attitude

OUT = Path(__file__).resolve().parent.parent / "docs" / "figures" / "spherical_2dof_basin.png"
RADII_DEG = (0.1, 0.3, 1.0, 2.0, 5.0, 10.0, 20.0, 30.0, 45.0, 60.0)


def _det_b_map(p, grid: np.ndarray) -> np.ndarray:
    """det B over a (roll, pitch) grid (rad); nan where the IK (eq. 8) has no solution."""
    out = np.full((grid.size, grid.size), np.nan)
    for a, roll in enumerate(grid):
        for b, pitch in enumerate(grid):
            try:
                theta = kin.inverse_kinematics(p, (roll, pitch), BRANCHES)
            except InvalidParameters:
                continue
            out[a, b] = np.linalg.det(kin.constraint_jacobians(p, theta, (roll, pitch))[1])
    return out


def main(directions: int = 24, grid_points: int = 91, out: Path = OUT) -> dict[str, list]:
    mech = load("spherical_2dof")
    radii = np.radians(RADII_DEG)
    poses = {"regular": REGULAR, "near singular": NEAR_SINGULAR}
    table = {name: basin_study(mech, pose, radii, directions) for name, pose in poses.items()}

    fig, axes = plt.subplots(1, 3, figsize=(16, 4.8))
    grid = np.radians(np.linspace(-30, 60, grid_points))
    det = _det_b_map(mech.params, grid)
    lim = np.nanmax(np.abs(det))
    im = axes[0].pcolormesh(
        np.degrees(grid), np.degrees(grid), det.T, cmap="RdBu_r", vmin=-lim, vmax=lim, shading="auto"
    )
    axes[0].contour(np.degrees(grid), np.degrees(grid), det.T, levels=[0.0], colors="k", linewidths=1.0)
    cone = np.degrees(cone_attitude(np.linspace(0, 2, 200))[0])
    axes[0].plot(cone[:, 0], cone[:, 1], "k--", lw=1, label="cone scene (half angle 15 deg)")
    for (name, pose), marker in zip(poses.items(), ("o", "x")):
        axes[0].plot(*np.degrees(pose), marker, color="k", ms=8, label=f"{name} target")
    axes[0].set(
        xlabel="roll phi_x (deg)",
        ylabel="pitch phi_y (deg)",
        title="det B (black: det B = 0; blank: IK undefined)",
    )
    axes[0].legend(fontsize=7, loc="lower right")
    fig.colorbar(im, ax=axes[0])
    styles = {"paper": "C0", "newton": "C1", "closure": "C2"}
    for name, ls in (("regular", "-"), ("near singular", ":")):
        for method in METHODS:
            rows = [r for r in table[name] if r.method == method]
            for ax, field in ((axes[1], "found"), (axes[2], "iterations")):
                ax.semilogx(
                    RADII_DEG,
                    [getattr(r, field) for r in rows],
                    ls,
                    color=styles[method],
                    marker="o",
                    ms=3,
                    label=f"{method}, {name}",
                )
    axes[1].set(
        xlabel="start distance from the answer (deg)",
        ylabel="fraction of starts finding the answer",
        title=f"FK convergence basin ({directions} directions per radius)",
    )
    axes[2].set(
        xlabel="start distance from the answer (deg)",
        ylabel="mean iterations (successful starts)",
        title="iterations to |step| (closure: |residual|) <= 1e-13",
    )
    axes[1].legend(fontsize=7)
    for ax in axes[1:]:
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=90)

    print(
        f"{'pose':14s} {'method':8s} {'r (deg)':>8s} {'found':>6s} {'other':>6s} {'failed':>6s} {'iters':>6s}"
    )
    for name, rows in table.items():
        for r in rows:
            print(
                f"{name:14s} {r.method:8s} {np.degrees(r.radius):8.1f} {r.found:6.2f} {r.elsewhere:6.2f} "
                f"{r.failed:6.2f} {r.iterations:6.2f}"
            )
    print(f"wrote {out}")
    return {name: [r.__dict__ for r in rows] for name, rows in table.items()}


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--directions", type=int, default=24)
    main(parser.parse_args().directions)
