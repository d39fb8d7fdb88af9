"""The engine gimbal's figures, drawn from the data of its studies (`studies`; matplotlib on use).

Each function writes one PNG into a folder and returns its path: `docs/figures/rocket_gimbal_*.png`
when run by `tools/figures.py rocket_gimbal`.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mechkit.base.plotting import pyplot, save_figure
from mechkit.mechanisms.rocket_gimbal.kinematics import RULE_ANGLE
from mechkit.mechanisms.rocket_gimbal.studies import SUPPORTS, Conditioning, Linearisation, Swing


def linearisation_figure(study: Linearisation, folder: Path) -> list[Path]:
    """Error maps of pitch and yaw over the stroke square, and the errors along the Table 1 lines.

    Args:
        study: the linearisation study.
        folder: where the PNG goes.

    Returns:
        The file written.
    """
    plt = pyplot("rocket_gimbal figures")
    e, deg = study.errors, np.degrees
    mm = 1e3 * e.stroke_a
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    err = deg(e.exact - e.linear)
    limit = np.abs(err).max()
    for k, (ax, title) in enumerate(zip(axes[:2], ("pitch theta_x", "yaw theta_y"))):
        im = ax.pcolormesh(mm, mm, err[:, :, k].T, cmap="RdBu_r", vmin=-limit, vmax=limit, shading="auto")
        ax.contour(mm, mm, err[:, :, k].T, levels=np.arange(-0.5, 0.51, 0.1), colors="k", linewidths=0.5)
        ax.set(
            xlabel="stroke dlA (mm)", ylabel="stroke dlB (mm)", title=f"{title}: exact - linear (deg)", aspect="equal"
        )
        fig.colorbar(im, ax=ax, label="error (deg)")
    ax = axes[2]
    for (name, v), style in zip(study.lines.items(), ("-", "--")):
        ax.plot(1e3 * study.sweep, deg(v[:, 0]), "C0" + style, label=f"theta_x error, {name}")
        ax.plot(1e3 * study.sweep, deg(v[:, 1]), "C3" + style, label=f"theta_y error, {name}")
    ax.set(xlabel="swept stroke (mm)", ylabel="exact - linear (deg)", title="the paper's Table 1 lines")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.suptitle(
        f"linear rule 110 mm <-> 6.5 deg: worst {deg(e.worst):.3f} deg ({100 * e.worst / RULE_ANGLE:.2f} % of "
        f"6.5 deg) at dlA, dlB = {1e3 * e.worst_at[0]:.0f}, {1e3 * e.worst_at[1]:.0f} mm; cross-talk "
        f"{deg(e.cross_talk):.3f} deg"
    )
    return [save_figure(fig, folder / "rocket_gimbal_linearisation.png")]


def conditioning_figure(study: Conditioning, folder: Path) -> list[Path]:
    """log10 of the in-range root's condition number and of its raw error over the stroke square.

    Args:
        study: the conditioning study.
        folder: where the PNG goes.

    Returns:
        The file written.
    """
    plt = pyplot("rocket_gimbal figures")
    grid = study.grid
    mm = 1e3 * grid.axis
    fig, axes = plt.subplots(1, 2, figsize=(11, 5.0))
    for ax, data, title in (
        (
            axes[0],
            np.log10(np.where(np.isfinite(grid.condition), grid.condition, np.nan)),
            "log10 condition of the in-range root",
        ),
        (axes[1], np.log10(np.maximum(grid.raw_error, 1e-17)), "log10 |raw root - Newton FK| (rad)"),
    ):
        im = ax.pcolormesh(mm, mm, data.T, shading="auto", cmap="viridis")
        ax.set(xlabel="stroke dlA (mm)", ylabel="stroke dlB (mm)", title=title, aspect="equal")
        fig.colorbar(im, ax=ax)
    fig.suptitle("resultant FK: digits are lost near dlA = dlB, where the in-range root meets a flipped mode's")
    return [save_figure(fig, folder / "rocket_gimbal_conditioning.png")]


def swing_figure(study: Swing, folder: Path) -> list[Path]:
    """Servo forces and support forces by both methods, and their worst relative difference, over the period.

    Args:
        study: the swing study.
        folder: where the PNG goes.

    Returns:
        The file written.
    """
    plt = pyplot("rocket_gimbal figures")
    times, rel = study.times, study.relative_difference
    pin_u, soc_u = study.efforts["pinocchio"], study.efforts["soc"]
    pin_f, soc_f = study.supports["pinocchio"], study.supports["soc"]
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.4))
    for k, name in enumerate(study.actuated):
        axes[0].plot(times, pin_u[:, k] / 1e3, f"C{k}-", label=f"{name} Pinocchio")
        axes[0].plot(times[::5], soc_u[::5, k] / 1e3, f"C{k}o", ms=4, label=f"{name} SOC")
    axes[0].set(xlabel="time (s)", ylabel="servo force (kN)", title="servo forces (conical swing, 1 Hz, +-4 deg)")
    for k, name in enumerate(SUPPORTS):
        norm_pin = np.linalg.norm(pin_f[:, k, :3], axis=1)
        norm_soc = np.linalg.norm(soc_f[:, k, :3], axis=1)
        scale = 1e6 if name == "bracket_hinge" else 1e3
        axes[1].plot(times, norm_pin / scale, f"C{k}-", label=f"{name} Pinocchio ({'MN' if scale == 1e6 else 'kN'})")
        axes[1].plot(times[::5], norm_soc[::5] / scale, f"C{k}o", ms=4, label=f"{name} SOC")
    axes[1].set(
        xlabel="time (s)",
        ylabel="|support force| (MN bearings, kN servo pivots)",
        title="support reactions on the gimbal frame side",
    )
    axes[2].semilogy(times, np.maximum(rel, 1e-17), "k-")
    axes[2].set(xlabel="time (s)", ylabel="max relative difference", title="Pinocchio vs SOC, every effort and joint")
    for ax in axes:
        ax.grid(True, alpha=0.3)
    for ax in axes[:2]:
        ax.legend(fontsize=7)
    return [save_figure(fig, folder / "rocket_gimbal_swing.png")]
