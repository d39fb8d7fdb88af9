"""The bench's figures (matplotlib, files only): error vs time per mechanism and quantity, cost vs size."""

from __future__ import annotations

from pathlib import Path
from types import ModuleType
from typing import TYPE_CHECKING

import numpy as np

from mechkit.base import plotting
from mechkit.base.atomic import write_files
from mechkit.bench.errors import ERROR_LABELS
from mechkit.bench.results import MechanismBench, Row
from mechkit.bench.scale import ScaleFit
from mechkit.catalog.contract import BENCH_QUANTITIES

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

#: Error shown on log charts for an exact result.
CHART_FLOOR = 1e-17


def pyplot() -> ModuleType:
    """matplotlib.pyplot on the Agg backend (files only, no window).

    Raises:
        MethodUnavailable: matplotlib is not installed.
    """
    return plotting.pyplot("bench charts")


def save_figure(fig: Figure, ax: Axes, folder: Path, stem: str, legend_size: int = 6) -> list[Path]:
    """Grid, legend, tight layout; write `folder/stem.png` and `.svg`; close the figure.

    Args:
        fig: the figure.
        ax: its axes.
        folder: where the files go (created).
        stem: the file name without extension.
        legend_size: the legend's font size (pt).

    Returns:
        The two paths written (PNG, SVG).
    """
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=legend_size)
    fig.tight_layout()
    try:
        rendered = {folder / f"{stem}.{ext}": plotting.figure_bytes(fig, ext) for ext in ("png", "svg")}
    finally:
        pyplot().close(fig)
    folder.mkdir(parents=True, exist_ok=True)
    return write_files(rendered)


def chart(b: MechanismBench, quantity: str, folder: Path) -> list[Path]:
    """Error vs time per call, log-log, one point per method, knob sweeps joined; PNG and SVG.

    Args:
        b: one mechanism's bench.
        quantity: a bench quantity (`BENCH_QUANTITIES`).
        folder: where the files go.

    Returns:
        The PNG and SVG written as `bench_<name>_<quantity>`, or none when no method of that quantity succeeded.
    """
    plt = pyplot()

    rows = [r for r in b.rows if r.method.quantity == quantity and r.outcome == "ok"]
    failed = [r for r in b.rows if r.method.quantity == quantity and r.outcome != "ok"]
    if not rows:
        return []
    fig, ax = plt.subplots(figsize=(8, 5.5))
    families: dict[str, list[Row]] = {}
    for r in rows:
        families.setdefault(r.method.family or r.method.name, []).append(r)
    markers = "osD^v<>ph*X"
    for k, (family, members) in enumerate(families.items()):
        t = np.array([r.median_s * 1e6 for r in members])
        e = np.array([max(r.error, CHART_FLOOR) for r in members])
        peer = members[0].method.peer
        style = {
            "marker": "s" if peer else markers[k % len(markers)],
            "markersize": 7,
            "linestyle": "--" if peer else "-",
            "markerfacecolor": "none" if peer else None,
        }
        label = ("[peer] " if peer else "") + family
        if len(members) > 1:
            ax.plot(t, e, label=label, **style)
            for r, ti, ei in zip(members, t, e):
                ax.annotate(
                    r.method.knob or r.method.name, (ti, ei), fontsize=6, xytext=(3, 3), textcoords="offset points"
                )
        else:
            style["linestyle"] = "none"
            ax.plot(t, e, label=label, **style)
    ax.axhline(CHART_FLOOR, color="grey", lw=0.5, ls=":")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time per call (microseconds, median)")
    ax.set_ylabel(f"error: {ERROR_LABELS[quantity]}")
    title = f"{b.name}: {quantity.replace('_', ' ')} (reference: {b.references.get(quantity, '?')})"
    ax.set_title(title if len(title) < 95 else title[:92] + "...", fontsize=9)
    if failed:
        ax.text(
            0.01, 0.01, "raised: " + "; ".join(r.method.name for r in failed)[:150], transform=ax.transAxes, fontsize=6
        )
    return save_figure(fig, ax, folder, f"bench_{b.name}_{quantity}", legend_size=7)


def scale_chart(fits: list[ScaleFit], folder: Path) -> list[Path]:
    """Cost vs model size (nv), log-log, one curve per method, fitted exponent in the legend.

    Args:
        fits: (method, [(mechanism, nv, seconds per call)], fitted exponent p) per method (`scale.scale_fits`).
        folder: where the files go.

    Returns:
        The PNG and SVG written as `bench_scale`, or none without fits.
    """
    plt = pyplot()

    if not fits:
        return []
    fig, ax = plt.subplots(figsize=(8, 5.5))
    for name, pts, slope in fits:
        ax.plot([p[1] for p in pts], [p[2] * 1e6 for p in pts], marker="o", label=f"{name} (p={slope:.2f})")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("model size nv (tree velocity coordinates)")
    ax.set_ylabel("time per call (microseconds, median)")
    ax.set_title("cost vs model size, fitted t ~ nv^p", fontsize=9)
    return save_figure(fig, ax, folder, "bench_scale")


def draw_all(results: list[MechanismBench], fits: list[ScaleFit], folder: Path) -> list[Path]:
    """Every mechanism's charts (one per quantity) and the scale chart, in `folder`.

    Args:
        results: the benches of the mechanisms.
        fits: the cost-against-size fits (`scale.scale_fits`).
        folder: where the files go.

    Returns:
        The files written.
    """
    paths: list[Path] = []
    with np.errstate(all="ignore"):  # matplotlib's own arithmetic
        for b in results:
            for quantity in BENCH_QUANTITIES:
                paths += chart(b, quantity, folder)
        paths += scale_chart(fits, folder)
    return paths
