"""The cone scene of the 2-DOF spherical platform: the paper's Figs. 5-7, plus its dynamics.

The platform normal sweeps a cone of apex angle 30 deg (half angle 15 deg) about Z0, one turn in
2 s. Panels: motor curves by the IK (eq. 8; Fig. 5); roll and pitch by the paper's FK of those
curves against the plan (Fig. 6); the marker point (tip of the unit normal) planned and recovered
(Fig. 7, top view); motor torques and the support moment about O, Pinocchio vs SOC. Writes
docs/figures/spherical_2dof_cone.png and prints the worst differences.
Usage: python tools/spherical_2dof_cone.py [--samples 72]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from mechkit.loading import load
from mechkit.mechanisms.spherical_2dof import kinematics as kin
from mechkit.mechanisms.spherical_2dof import soc
from mechkit.mechanisms.spherical_2dof.kinematics import BRANCHES, platform_normal
from mechkit.mechanisms.spherical_2dof.scenes import cone_attitude, cone_times
from mechkit.mechanisms.spherical_2dof.tree import state

OUT = Path(__file__).resolve().parent.parent / "docs" / "figures" / "spherical_2dof_cone.png"


def main(samples: int = 72, out: Path = OUT) -> dict[str, float]:
    mech = load("spherical_2dof")
    p = mech.params
    t = cone_times(samples)
    phi, phi_d, phi_dd = cone_attitude(t)
    theta = np.array([kin.inverse_kinematics(p, x, BRANCHES) for x in phi])
    fk = np.zeros_like(phi)
    start = np.zeros(2)  # the calibrated home pose P0
    for k, th in enumerate(theta):
        start = fk[k] = kin.fk_paper(p, th, start, BRANCHES).phi
    pin_u, soc_u, pin_m, soc_m = [], [], [], []
    for k in range(samples):
        q, v, a = state(mech, phi[k], phi_d[k], phi_dd[k])
        ref = mech.inverse_dynamics(q, v, a)
        ours = soc.solve(p, phi[k], phi_d[k], phi_dd[k], BRANCHES)
        pin_u.append([ref.efforts[j] for j in mech.actuated])
        soc_u.append([ours.efforts[j] for j in mech.actuated])
        pin_m.append(ref.reactions["hooke_roll"].wrench[3:])
        soc_m.append(ours.reactions["hooke_roll"][3:])
    pin_u, soc_u, pin_m, soc_m = map(np.asarray, (pin_u, soc_u, pin_m, soc_m))

    fig, ax = plt.subplots(1, 4, figsize=(19, 4.4))
    deg = np.degrees
    for k, name in enumerate(("theta_11 (r11)", "theta_21 (r21)")):
        ax[0].plot(t, deg(theta[:, k]), label=name)
    ax[0].set(
        xlabel="time (s)", ylabel="motor angle (deg)", title="motor curves by IK eq. (8) (paper Fig. 5)"
    )
    for k, name in enumerate(("roll phi_x", "pitch phi_y")):
        ax[1].plot(t, deg(phi[:, k]), "--", color=f"C{k}", label=f"{name}, plan")
        ax[1].plot(t, deg(fk[:, k]), "*", color=f"C{k}", ms=4, label=f"{name}, paper FK")
    ax[1].set(xlabel="time (s)", ylabel="attitude (deg)", title="FK of the motor curves (paper Fig. 6)")
    n_plan, n_fk = platform_normal(phi), platform_normal(fk)
    ax[2].plot(n_plan[:, 0], n_plan[:, 1], "--", label="planned")
    ax[2].plot(n_fk[:, 0], n_fk[:, 1], "*", ms=4, label="from paper FK")
    ax[2].set(
        xlabel="marker x (unit normal tip, -)",
        ylabel="marker y (-)",
        aspect="equal",
        title="marker point, top view (paper Fig. 7)",
    )
    for k, name in enumerate(mech.actuated):
        ax[3].plot(t, pin_u[:, k], color=f"C{k}", label=f"torque {name}, Pinocchio")
        ax[3].plot(t, soc_u[:, k], "x", color=f"C{k}", ms=4, label=f"torque {name}, SOC")
    for k, axis in ((1, "y"), (2, "z")):
        ax[3].plot(t, pin_m[:, k], color=f"C{k + 2}", label=f"support moment m{axis}, Pinocchio")
        ax[3].plot(t, soc_m[:, k], "+", color=f"C{k + 2}", ms=5, label=f"support moment m{axis}, SOC")
    ax[3].set(xlabel="time (s)", ylabel="N m", title="motor torques and support moment about O")
    for a in ax:
        a.grid(True, alpha=0.3)
        a.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=80)

    errors = {
        "FK vs plan, attitude (rad)": float(np.abs(fk - phi).max()),
        "FK vs plan, marker point (-)": float(np.linalg.norm(n_fk - n_plan, axis=1).max()),
        "torques Pinocchio vs SOC (N m)": float(np.abs(pin_u - soc_u).max()),
        "support moment Pinocchio vs SOC (N m)": float(np.abs(pin_m - soc_m).max()),
        "peak |torque| (N m)": float(np.abs(pin_u).max()),
        "peak |support moment| (N m)": float(np.abs(pin_m).max()),
    }
    for name, value in errors.items():
        print(f"{name:40s} {value:.3e}")
    print(f"wrote {out}")
    return errors


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=72)
    main(parser.parse_args().samples)
