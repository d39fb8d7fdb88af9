"""Servo forces and gimbal support reactions over one period of the swing, Pinocchio vs SOC.

Writes docs/figures/rocket_gimbal_swing.png (forces by both methods and their relative difference)
and prints the peaks and the worst relative differences.
Usage: python tools/rocket_gimbal_swing.py [--n 101]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from mechkit.loading import load
from mechkit.mechanisms.rocket_gimbal.scenes import SwingScene, thrust_fext
from mechkit.mechanisms.rocket_gimbal.soc import soc_skcs
from mechkit.mechanisms.rocket_gimbal.state import joint_state
from mechkit.validation.soc import solve_soc

OUT = Path(__file__).resolve().parent.parent / "docs" / "figures" / "rocket_gimbal_swing.png"
SUPPORTS = ("bracket_hinge", "a_swing_1", "b_swing_1")


def main(n: int = 101, out: Path = OUT) -> dict[str, float]:
    mech = load("rocket_gimbal")
    scene = SwingScene()
    times = np.linspace(0.0, 1.0 / scene.frequency, n)
    pin_u, soc_u, pin_f, soc_f, rel = [], [], [], [], []
    for t in times:
        motion = scene.motion(mech.params, t)
        q, v, a = joint_state(mech, motion)
        r = mech.inverse_dynamics(q, v, a, fext=thrust_fext(mech, q, scene))
        s = solve_soc(soc_skcs(mech.params, motion, scene))
        pin_u.append([r.efforts[j] for j in mech.actuated])
        soc_u.append([s.efforts[j] for j in mech.actuated])
        pin_f.append([r.reactions[j].wrench for j in SUPPORTS])
        soc_f.append([s.reactions[j] for j in SUPPORTS])
        diffs = [abs(r.efforts[j] - s.efforts[j]) / abs(r.efforts[j]) for j in mech.actuated]
        diffs += [
            np.abs(r.reactions[j].wrench - s.reactions[j]).max() / np.abs(r.reactions[j].wrench).max()
            for j in r.reactions
        ]
        rel.append(max(diffs))
    pin_u, soc_u, pin_f, soc_f = map(np.array, (pin_u, soc_u, pin_f, soc_f))

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.4))
    for k, name in enumerate(mech.actuated):
        axes[0].plot(times, pin_u[:, k] / 1e3, f"C{k}-", label=f"{name} Pinocchio")
        axes[0].plot(times[::5], soc_u[::5, k] / 1e3, f"C{k}o", ms=4, label=f"{name} SOC")
    axes[0].set(
        xlabel="time (s)", ylabel="servo force (kN)", title="servo forces (conical swing, 1 Hz, +-4 deg)"
    )
    for k, name in enumerate(SUPPORTS):
        norm_pin = np.linalg.norm(pin_f[:, k, :3], axis=1)
        norm_soc = np.linalg.norm(soc_f[:, k, :3], axis=1)
        scale = 1e6 if name == "bracket_hinge" else 1e3
        axes[1].plot(
            times, norm_pin / scale, f"C{k}-", label=f"{name} Pinocchio ({'MN' if scale == 1e6 else 'kN'})"
        )
        axes[1].plot(times[::5], norm_soc[::5] / scale, f"C{k}o", ms=4, label=f"{name} SOC")
    axes[1].set(
        xlabel="time (s)",
        ylabel="|support force| (MN bearings, kN servo pivots)",
        title="support reactions on the gimbal frame side",
    )
    axes[2].semilogy(times, np.maximum(rel, 1e-17), "k-")
    axes[2].set(
        xlabel="time (s)", ylabel="max relative difference", title="Pinocchio vs SOC, every effort and joint"
    )
    for ax in axes:
        ax.grid(True, alpha=0.3)
    for ax in axes[:2]:
        ax.legend(fontsize=7)
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=90)
    plt.close(fig)
    return {
        "peak servo force (kN)": float(np.abs(pin_u).max() / 1e3),
        "bearing force min (MN)": float(np.linalg.norm(pin_f[:, 0, :3], axis=1).min() / 1e6),
        "bearing force max (MN)": float(np.linalg.norm(pin_f[:, 0, :3], axis=1).max() / 1e6),
        "peak servo pivot force (kN)": float(np.linalg.norm(pin_f[:, 1:, :3], axis=2).max() / 1e3),
        "worst relative difference Pinocchio vs SOC": float(max(rel)),
    }


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=101, help="instants over one period")
    parser.add_argument("--out", type=Path, default=OUT)
    args = parser.parse_args()
    for key, value in main(args.n, args.out).items():
        print(f"{key}: {value:.6g}")
