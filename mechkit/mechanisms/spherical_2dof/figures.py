"""The 2-DOF spherical platform's figures, drawn from the data of its studies (`studies`; matplotlib
on use): `spherical_2dof_cone.png` (the paper's Figs. 5-7 and the dynamics) and
`spherical_2dof_basin.png` (det B and the FK's basins), in the folder given (docs/figures when run
by `tools/figures.py spherical_2dof`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mechkit.base.plotting import pyplot, save_figure
from mechkit.mechanisms.spherical_2dof.fk import METHODS
from mechkit.mechanisms.spherical_2dof.kinematics import platform_normal
from mechkit.mechanisms.spherical_2dof.scenes import cone_attitude
from mechkit.mechanisms.spherical_2dof.studies import RADII_DEG, Basin, Cone


def cone_figure(c: Cone, folder: Path) -> list[Path]:
    """Motor curves, FK against the plan, the marker point from above, torques and support moment.

    Args:
        c: the cone study.
        folder: where the PNG goes.

    Returns:
        The file written.
    """
    plt = pyplot("spherical_2dof figures")
    fig, ax = plt.subplots(1, 4, figsize=(19, 4.4))
    deg = np.degrees
    for k, name in enumerate(("theta_11 (r11)", "theta_21 (r21)")):
        ax[0].plot(c.t, deg(c.theta[:, k]), label=name)
    ax[0].set(xlabel="time (s)", ylabel="motor angle (deg)", title="motor curves by IK eq. (8) (paper Fig. 5)")
    for k, name in enumerate(("roll phi_x", "pitch phi_y")):
        ax[1].plot(c.t, deg(c.phi[:, k]), "--", color=f"C{k}", label=f"{name}, plan")
        ax[1].plot(c.t, deg(c.fk[:, k]), "*", color=f"C{k}", ms=4, label=f"{name}, paper FK")
    ax[1].set(xlabel="time (s)", ylabel="attitude (deg)", title="FK of the motor curves (paper Fig. 6)")
    n_plan, n_fk = platform_normal(c.phi), platform_normal(c.fk)
    ax[2].plot(n_plan[:, 0], n_plan[:, 1], "--", label="planned")
    ax[2].plot(n_fk[:, 0], n_fk[:, 1], "*", ms=4, label="from paper FK")
    ax[2].set(
        xlabel="marker x (unit normal tip, -)",
        ylabel="marker y (-)",
        aspect="equal",
        title="marker point, top view (paper Fig. 7)",
    )
    for k, name in enumerate(c.actuated):
        ax[3].plot(c.t, c.efforts["pinocchio"][:, k], color=f"C{k}", label=f"torque {name}, Pinocchio")
        ax[3].plot(c.t, c.efforts["soc"][:, k], "x", color=f"C{k}", ms=4, label=f"torque {name}, SOC")
    for k, axis in ((1, "y"), (2, "z")):
        ax[3].plot(c.t, c.support["pinocchio"][:, k], color=f"C{k + 2}", label=f"support moment m{axis}, Pinocchio")
        ax[3].plot(c.t, c.support["soc"][:, k], "+", color=f"C{k + 2}", ms=5, label=f"support moment m{axis}, SOC")
    ax[3].set(xlabel="time (s)", ylabel="N m", title="motor torques and support moment about O")
    for a in ax:
        a.grid(True, alpha=0.3)
        a.legend(fontsize=7)
    return [save_figure(fig, folder / "spherical_2dof_cone.png", dpi=80)]


def basin_figure(b: Basin, folder: Path) -> list[Path]:
    """det B over (roll, pitch) with the cone and the targets; per method, the fraction of starts that
    find the answer and the mean iterations, against the start distance.

    Args:
        b: the basin study.
        folder: where the PNG goes.

    Returns:
        The file written.
    """
    plt = pyplot("spherical_2dof figures")
    fig, axes = plt.subplots(1, 3, figsize=(16, 4.8))
    grid_deg = np.degrees(b.grid)
    lim = np.nanmax(np.abs(b.det_b))
    im = axes[0].pcolormesh(grid_deg, grid_deg, b.det_b.T, cmap="RdBu_r", vmin=-lim, vmax=lim, shading="auto")
    axes[0].contour(grid_deg, grid_deg, b.det_b.T, levels=[0.0], colors="k", linewidths=1.0)
    cone = np.degrees(cone_attitude(np.linspace(0, 2, 200))[0])
    axes[0].plot(cone[:, 0], cone[:, 1], "k--", lw=1, label="cone scene (half angle 15 deg)")
    for (name, pose), marker in zip(b.poses.items(), ("o", "x")):
        axes[0].plot(*np.degrees(pose), marker, color="k", ms=8, label=f"{name} target")
    axes[0].set(
        xlabel="roll phi_x (deg)", ylabel="pitch phi_y (deg)", title="det B (black: det B = 0; blank: IK undefined)"
    )
    axes[0].legend(fontsize=7, loc="lower right")
    fig.colorbar(im, ax=axes[0])
    styles = {"paper": "C0", "newton": "C1", "closure": "C2"}
    for name, ls in (("regular", "-"), ("near singular", ":")):
        for method in METHODS:
            rows = [r for r in b.rows[name] if r.method == method]
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
        title=f"FK convergence basin ({b.directions} directions per radius)",
    )
    axes[2].set(
        xlabel="start distance from the answer (deg)",
        ylabel="mean iterations (successful starts)",
        title="iterations to |step| (closure: |residual|) <= 1e-13",
    )
    axes[1].legend(fontsize=7)
    for ax in axes[1:]:
        ax.grid(True, which="both", alpha=0.3)
    return [save_figure(fig, folder / "spherical_2dof_basin.png")]
