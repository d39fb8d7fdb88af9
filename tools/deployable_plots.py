"""Figures of the 9RR-12URU fold like the paper's Fig. 7-9, plus the drive laws and drive torques.

Solves the 200 s fold (closure at every `--step` s, warm start), compares the model with the
paper's eq. (6)-(13) (our reading, see docs/mechanisms/deployable_9rr12uru.md) and writes
docs/figures/deployable_{drives,node_F,node_I_speed,node_B_rpy,efforts}.png; prints the worst
deviations.
Usage: python tools/deployable_plots.py [--step 1.0]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from mechkit.base.spatial import rot_y
from mechkit.loading import load
from mechkit.mechanisms.truss.drives import drive_state
from mechkit.mechanisms.truss.fold import fold, fold_times
from mechkit.mechanisms.truss.geometry import R_B0_ANGLES, euler_xyz, rot_axis, rpy_angles
from mechkit.mechanisms.truss.nodes import node_positions, node_velocity

FIGURES = Path(__file__).resolve().parent.parent / "docs" / "figures"
PAPER_END_GAMMA_X = 85.5133  # deg, section 3.2 (theory; Adams 84.9368)


def _save(fig, name: str, folder: Path) -> Path:
    path = folder / f"deployable_{name}.png"
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return path


def main(step: float = 1.0, folder: Path = FIGURES) -> dict[str, float]:
    folder.mkdir(parents=True, exist_ok=True)
    mech = load("deployable_9rr12uru")
    p, g = mech.params, mech.params.geometry()
    samples = fold(mech, fold_times(step))
    t = np.array([s.t for s in samples])
    states = [drive_state(x) for x in t]
    node_b = mech.model.getFrameId("node_B")
    b_initial = rot_y(p.gamma_ref) @ euler_xyz(R_B0_ANGLES)  # paper's node-B frame at t = 0, A axes
    rows = []
    for sample, s in zip(samples, states):
        eq = g.node_positions(s.alpha, s.gamma)
        model = node_positions(mech, sample.q)
        rpy_model = rpy_angles(mech.data.oMf[node_b].rotation @ b_initial)
        printed = rpy_angles(rot_y(s.gamma) @ rot_axis(g.tangent("B"), s.gamma - p.gamma_ref) @ euler_xyz(R_B0_ANGLES))
        efforts = mech.inverse_dynamics(sample.q, sample.v, sample.a, determinacy=False).efforts
        rows.append({
            "F_eq": eq["F"], "F_model": model["F"],
            "pos_err": max(np.abs(model[k] - eq[k]).max() for k in model),
            "I_speed_eq": np.linalg.norm(g.node_velocities(s.alpha, s.gamma, s.alpha_rate, s.gamma_rate)["I"]),
            "I_speed_model": np.linalg.norm(node_velocity(mech, sample.q, sample.v, "I")),
            "rpy_eq": g.node_rpy("B", s.gamma, p.gamma_ref), "rpy_model": rpy_model, "rpy_printed": printed,
            "residual": np.abs(mech.closure_residual(sample.q)).max(), "efforts": efforts})

    deg = np.degrees
    fig, ax = plt.subplots(figsize=(7, 3.6))
    ax.plot(t, deg([s.alpha for s in states]), label="fold alpha(t)")
    ax.plot(t, deg([s.gamma for s in states]), label="tilt gamma(t) = -acos(...)")
    ax.set(xlabel="time t (s)", ylabel="angle (deg)", title="Drive laws of section 3.2 (our sign of gamma)")
    ax.legend(), ax.grid(alpha=0.3)
    _save(fig, "drives", folder)

    fig, ax = plt.subplots(figsize=(7, 3.8))
    for k, axis in enumerate("xyz"):
        ax.plot(t, [1e3 * r["F_eq"][k] for r in rows], color=f"C{k}", label=f"{axis}, eq. (7)-(8)")
        ax.plot(t[::10], [1e3 * r["F_model"][k] for r in rows[::10]], "o", color=f"C{k}", mfc="none", label=f"{axis}, model")
    ax.set(xlabel="time t (s)", ylabel="position of node F (mm)", title="Node F centre (cf. paper Fig. 7)")
    ax.legend(ncol=2, fontsize=8), ax.grid(alpha=0.3)
    _save(fig, "node_F", folder)

    fig, ax = plt.subplots(figsize=(7, 3.6))
    ax.plot(t, [1e3 * r["I_speed_eq"] for r in rows], label="d/dt of eq. (8)")
    ax.plot(t[::10], [1e3 * r["I_speed_model"] for r in rows[::10]], "o", mfc="none", label="model (closure velocities)")
    ax.set(xlabel="time t (s)", ylabel="speed of node I (mm/s)", title="Node I centre speed (cf. paper Fig. 8)")
    ax.legend(), ax.grid(alpha=0.3)
    _save(fig, "node_I_speed", folder)

    fig, axes = plt.subplots(3, 1, figsize=(7, 7.5), sharex=True)
    for k, name in enumerate(("gamma_x", "gamma_y", "gamma_z")):
        ax = axes[k]
        eq, model = np.unwrap([r["rpy_eq"][k] for r in rows]), np.unwrap([r["rpy_model"][k] for r in rows])
        ax.plot(t, deg(eq), label="eq. (9)-(13), our reading")
        ax.plot(t[::10], deg(model[::10]), "o", mfc="none", label="model")
        ax.plot(t, deg(np.unwrap([r["rpy_printed"][k] for r in rows])), "--", label="eq. (9) as printed (+ about S4)")
        ax.set(ylabel=f"{name} (deg)"), ax.grid(alpha=0.3)
    axes[0].plot([200.0], [PAPER_END_GAMMA_X], "k*", label="paper, t = 200 s (85.51 deg)")
    axes[0].legend(fontsize=7)
    axes[0].set_title("RPY angles of node B (cf. paper Fig. 9; R_B0 read as Rx Ry Rz)")
    axes[2].set_xlabel("time t (s)")
    _save(fig, "node_B_rpy", folder)

    fig, ax = plt.subplots(figsize=(7, 3.8))
    for joint in mech.actuated:
        ax.plot(t, [r["efforts"][joint] for r in rows], label=joint)
    ax.set(xlabel="time t (s)", ylabel="drive torque (N m)",
           title="Drive torques along the fold, constrained RNEA (gravity -z, our masses)")
    ax.legend(ncol=4, fontsize=8), ax.grid(alpha=0.3)
    _save(fig, "efforts", folder)

    worst = {
        "node_position": max(r["pos_err"] for r in rows),
        "closure_residual": max(r["residual"] for r in rows),
        "node_I_speed": max(abs(r["I_speed_eq"] - r["I_speed_model"]) for r in rows),
        "node_B_rpy": max(np.abs(np.angle(np.exp(1j * (r["rpy_eq"] - r["rpy_model"])))).max() for r in rows),
        "gamma_x_end_deg": float(deg(rows[-1]["rpy_eq"][0])),
        "gamma_x_end_printed_deg": float(deg(rows[-1]["rpy_printed"][0])),
    }
    for key, value in worst.items():
        print(f"{key:26s} {value:.3e}")
    return worst


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--step", type=float, default=1.0, help="sampling step of the fold, s")
    main(parser.parse_args().step)
