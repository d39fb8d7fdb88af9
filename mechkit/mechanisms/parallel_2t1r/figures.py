"""The 2T1R's figures, drawn from the data of its studies (`studies`; matplotlib on use).

`parallel_2t1r_comparison.png` (SOC vs Pinocchio vs classic virtual work along the motion law) and
`parallel_2t1r_singular.png` (the singular studies), in the folder given (docs/figures when run by
`tools/figures.py parallel_2t1r`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mechkit.base.plotting import pyplot, save_figure
from mechkit.mechanisms.parallel_2t1r.compare import QUANTITIES, Comparison
from mechkit.mechanisms.parallel_2t1r.studies import SingularStudies

#: Panels of the comparison: (title, unit, quantities).
GROUPS = (
    ("driving torques", "N m", ("M1", "M2", "M3")),
    ("R23 (link22 on platform)", "N", ("R23_fx", "R23_fz")),
    ("R43 (link42 on platform)", "N", ("R43_fx", "R43_fz")),
)
DPI = 80


def comparison_figure(cmp: Comparison, folder: Path) -> list[Path]:
    """Values (SOC dashed over Pinocchio) and |method - Pinocchio| on a log axis, per group.

    Args:
        cmp: the comparison.
        folder: where the PNG goes.

    Returns:
        The file written.
    """
    plt = pyplot("parallel_2t1r figures")
    fig, axes = plt.subplots(2, 3, figsize=(15, 7.5), sharex=True)
    for col, (title, unit, names) in enumerate(GROUPS):
        top, bottom = axes[0, col], axes[1, col]
        for name in names:
            k = QUANTITIES.index(name)
            (line,) = top.plot(cmp.times, cmp.values["pinocchio"][:, k], lw=2.5, alpha=0.5, label=f"{name} Pinocchio")
            top.plot(cmp.times, cmp.values["soc"][:, k], "--", color=line.get_color(), lw=1, label=f"{name} SOC")
            for method, style in (("soc", "-"), ("classic", ":")):
                diff = np.abs(cmp.values[method][:, k] - cmp.values["pinocchio"][:, k])
                if np.all(np.isnan(diff)):
                    continue
                bottom.semilogy(
                    cmp.times,
                    np.maximum(diff, 1e-17),
                    style,
                    color=line.get_color(),
                    label=f"{name} |{method} - Pinocchio|",
                )
        top.set(title=title, ylabel=f"value ({unit})")
        bottom.set(xlabel="time t (s)", ylabel=f"difference ({unit})")
        top.legend(fontsize=7)
        bottom.legend(fontsize=7)
        top.grid(alpha=0.3)
        bottom.grid(alpha=0.3, which="both")
    fig.suptitle(
        "2T1R along theta = (pi t/18, pi t/15, pi t/10): Pinocchio constrained RNEA vs SOC vs classic "
        "virtual work (in-plane reaction forces, world frame)"
    )
    return [save_figure(fig, folder / "parallel_2t1r_comparison.png", DPI)]


def singular_figure(s: SingularStudies, folder: Path) -> list[Path]:
    """Log-log: the motion law's start (t -> 0) and theta_1 -> theta_2 for both actuation variants.

    Args:
        s: the singular studies.
        folder: where the PNG goes.

    Returns:
        The file written.
    """
    plt = pyplot("parallel_2t1r figures")
    start, approach = s.start, s.approach
    fig, (left, right) = plt.subplots(1, 2, figsize=(14, 5.5))
    for key, label in (
        ("cond_Jp", "cond J_p"),
        ("pinocchio:R13_fx", "|R13 fx| Pinocchio (N)"),
        ("pinocchio:M1", "|M1| Pinocchio (N m)"),
        ("soc:M1", "|M1| SOC (N m)"),
        ("soc:cond", "cond SOC (worst SKC)"),
    ):
        ok = np.isfinite(start.values[key])
        left.loglog(start.x[ok], np.abs(start.values[key][ok]), "o-", ms=3, label=label)
    left.set(
        xlabel="time t (s) after the singular start",
        ylabel="magnitude",
        title="motion law near t = 0 (double root of C1; torques tend to finite limits)",
    )
    for key, label, style in (
        ("cond_Jp", "cond J_p", "k-"),
        ("pinocchio:M1", "|M1| 3 motors", "C0-"),
        ("pinocchio:R13_fx", "|R13 fx| 3 motors", "C1-"),
        ("pinocchio:R23_fz", "|R23 fz| 3 motors", "C2-"),
        ("redundant/classic:M1", "|M1| 4 motors, min-norm", "C0--"),
        ("redundant/classic:M4", "|M4| 4 motors, min-norm", "C3--"),
        ("redundant/pinocchio:R13_fx", "|R13 fx| 4 motors", "C1--"),
        ("redundant/classic:cond", "cond J_a, 4 motors", "k--"),
    ):
        ok = np.isfinite(approach.values[key]) & (approach.x > 0)
        right.loglog(approach.x[ok], np.abs(approach.values[key][ok]), style, marker="o", ms=3, label=label)
    right.invert_xaxis()
    right.set(
        xlabel="theta_2 - theta_1 (rad), theta_2 = 20 deg, theta_3 = 30 deg, at rest",
        ylabel="magnitude (N m, N, -)",
        title="driving theta_1 onto theta_2: five-bar singularity",
    )
    for ax in (left, right):
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    return [save_figure(fig, folder / "parallel_2t1r_singular.png", DPI)]
