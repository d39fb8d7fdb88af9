"""Error map of the linear stroke-angle rule (110 mm <-> 6.5 deg) of the engine gimbal.

Writes docs/figures/rocket_gimbal_linearisation.png and prints the worst error (deg and % of
6.5 deg), where it occurs, the pitch-yaw cross-talk and the worst error along the paper's Table 1
lines (one stroke held at -10 / -8 mm). Usage: python tools/rocket_gimbal_linearisation.py [--n 45]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from mechkit.mechanisms.rocket_gimbal.kinematics import (
    RULE_ANGLE,
    RULE_STROKE,
    fk_newton,
    linear_rule,
    linear_rule_errors,
    pitch_yaw,
)
from mechkit.mechanisms.rocket_gimbal.params import RocketGimbalParams, geometry

OUT = Path(__file__).resolve().parent.parent / "docs" / "figures" / "rocket_gimbal_linearisation.png"


def main(n: int = 45, out: Path = OUT) -> dict[str, float]:
    geo = geometry(RocketGimbalParams())
    e = linear_rule_errors(geo, RULE_STROKE, RULE_ANGLE, n)
    mm, deg = 1e3 * e.stroke_a, np.degrees
    sweep = np.linspace(-RULE_STROKE, RULE_STROKE, 89)
    lines = {
        "dlA = -10 mm": [np.array([-0.010, s]) for s in sweep],
        "dlB = -8 mm": [np.array([s, -0.008]) for s in sweep],
    }
    line_err = {
        k: np.array([pitch_yaw(*fk_newton(geo, s)) - linear_rule(s) for s in v]) for k, v in lines.items()
    }
    table_worst = max(np.abs(v).max() for v in line_err.values())

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    err = deg(e.exact - e.linear)
    limit = np.abs(err).max()
    for k, (ax, title) in enumerate(zip(axes[:2], ("pitch theta_x", "yaw theta_y"))):
        im = ax.pcolormesh(mm, mm, err[:, :, k].T, cmap="RdBu_r", vmin=-limit, vmax=limit, shading="auto")
        ax.contour(mm, mm, err[:, :, k].T, levels=np.arange(-0.5, 0.51, 0.1), colors="k", linewidths=0.5)
        ax.set(
            xlabel="stroke dlA (mm)",
            ylabel="stroke dlB (mm)",
            title=f"{title}: exact - linear (deg)",
            aspect="equal",
        )
        fig.colorbar(im, ax=ax, label="error (deg)")
    ax = axes[2]
    for (name, v), style in zip(line_err.items(), ("-", "--")):
        ax.plot(1e3 * sweep, deg(v[:, 0]), "C0" + style, label=f"theta_x error, {name}")
        ax.plot(1e3 * sweep, deg(v[:, 1]), "C3" + style, label=f"theta_y error, {name}")
    ax.set(xlabel="swept stroke (mm)", ylabel="exact - linear (deg)", title="the paper's Table 1 lines")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.suptitle(
        f"linear rule 110 mm <-> 6.5 deg: worst {deg(e.worst):.3f} deg "
        f"({100 * e.worst / RULE_ANGLE:.2f} % of 6.5 deg) at dlA, dlB = "
        f"{1e3 * e.worst_at[0]:.0f}, {1e3 * e.worst_at[1]:.0f} mm; cross-talk {deg(e.cross_talk):.3f} deg"
    )
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=90)
    plt.close(fig)
    return {
        "worst_deg": float(deg(e.worst)),
        "worst_percent": float(100 * e.worst / RULE_ANGLE),
        "worst_at_mm": tuple(float(1e3 * x) for x in e.worst_at),
        "cross_talk_deg": float(deg(e.cross_talk)),
        "table1_lines_worst_deg": float(deg(table_worst)),
    }


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=45, help="grid points per stroke axis (odd)")
    parser.add_argument("--out", type=Path, default=OUT)
    args = parser.parse_args()
    for key, value in main(args.n, args.out).items():
        print(f"{key}: {value}")
