"""The composite's fold figures, like the paper's Fig. 7-9, plus the drive laws and drive torques,
drawn from `studies.fold_study` (matplotlib on use): `deployable_{drives,node_F,node_I_speed,
node_B_rpy,efforts}.png` in the folder given (docs/figures when run by `tools/figures.py
deployable_9rr12uru`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mechkit.base.plotting import pyplot, save_figure
from mechkit.mechanisms.deployable_9rr12uru.studies import PAPER_END_GAMMA_X, Fold


def fold_figures(f: Fold, folder: Path) -> list[Path]:
    """The five figures of the fold: drives, node F, node I's speed, node B's RPY, efforts.

    Args:
        f: the fold study.
        folder: where the PNGs go.

    Returns:
        The files written.
    """
    plt = pyplot("deployable figures")
    t, rows, deg, out = f.t, f.rows, np.degrees, []
    fig, ax = plt.subplots(figsize=(7, 3.6))
    ax.plot(t, deg([s.alpha for s in f.drives]), label="fold alpha(t)")
    ax.plot(t, deg([s.gamma for s in f.drives]), label="tilt gamma(t) = -acos(...)")
    ax.set(xlabel="time t (s)", ylabel="angle (deg)", title="Drive laws of section 3.2 (our sign of gamma)")
    ax.legend(), ax.grid(alpha=0.3)
    out.append(save_figure(fig, folder / "deployable_drives.png"))

    fig, ax = plt.subplots(figsize=(7, 3.8))
    for k, axis in enumerate("xyz"):
        ax.plot(t, [1e3 * r.node_f_eq[k] for r in rows], color=f"C{k}", label=f"{axis}, eq. (7)-(8)")
        ax.plot(
            t[::10],
            [1e3 * r.node_f_model[k] for r in rows[::10]],
            "o",
            color=f"C{k}",
            mfc="none",
            label=f"{axis}, model",
        )
    ax.set(xlabel="time t (s)", ylabel="position of node F (mm)", title="Node F centre (cf. paper Fig. 7)")
    ax.legend(ncol=2, fontsize=8), ax.grid(alpha=0.3)
    out.append(save_figure(fig, folder / "deployable_node_F.png"))

    fig, ax = plt.subplots(figsize=(7, 3.6))
    ax.plot(t, [1e3 * r.node_i_speed_eq for r in rows], label="d/dt of eq. (8)")
    ax.plot(
        t[::10], [1e3 * r.node_i_speed_model for r in rows[::10]], "o", mfc="none", label="model (closure velocities)"
    )
    ax.set(xlabel="time t (s)", ylabel="speed of node I (mm/s)", title="Node I centre speed (cf. paper Fig. 8)")
    ax.legend(), ax.grid(alpha=0.3)
    out.append(save_figure(fig, folder / "deployable_node_I_speed.png"))

    fig, axes = plt.subplots(3, 1, figsize=(7, 7.5), sharex=True)
    for k, name in enumerate(("gamma_x", "gamma_y", "gamma_z")):
        ax = axes[k]
        eq, model = np.unwrap([r.rpy_eq[k] for r in rows]), np.unwrap([r.rpy_model[k] for r in rows])
        ax.plot(t, deg(eq), label="eq. (9)-(13), our reading")
        ax.plot(t[::10], deg(model[::10]), "o", mfc="none", label="model")
        ax.plot(t, deg(np.unwrap([r.rpy_printed[k] for r in rows])), "--", label="eq. (9) as printed (+ about S4)")
        ax.set(ylabel=f"{name} (deg)"), ax.grid(alpha=0.3)
    axes[0].plot([200.0], [PAPER_END_GAMMA_X], "k*", label="paper, t = 200 s (85.51 deg)")
    axes[0].legend(fontsize=7)
    axes[0].set_title("RPY angles of node B (cf. paper Fig. 9; R_B0 read as Rx Ry Rz)")
    axes[2].set_xlabel("time t (s)")
    out.append(save_figure(fig, folder / "deployable_node_B_rpy.png"))

    fig, ax = plt.subplots(figsize=(7, 3.8))
    for joint in f.actuated:
        ax.plot(t, [r.efforts[joint] for r in rows], label=joint)
    ax.set(
        xlabel="time t (s)",
        ylabel="drive torque (N m)",
        title="Drive torques along the fold, constrained RNEA (gravity -z, our masses)",
    )
    ax.legend(ncol=4, fontsize=8), ax.grid(alpha=0.3)
    out.append(save_figure(fig, folder / "deployable_efforts.png"))
    return out
