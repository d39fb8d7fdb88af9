"""Pictures of a sweep's rows: a metric over two parameters (heat map), the Pareto front of two metrics.

Both take the DataFrame `mechkit.sweep.read` returns and write a PNG (matplotlib, the `bench` extra);
designs whose status is not "ok" are shown apart (grey cells, grey crosses), never dropped silently.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from mechkit.base.exceptions import InvalidParameters
from mechkit.base.plotting import pyplot, save_figure


def _columns(frame: pd.DataFrame, *names: str) -> None:
    for name in names:
        if name not in frame.columns:
            raise InvalidParameters("column", name, f"the rows have the columns {', '.join(frame.columns)}")


def pareto_mask(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """True for the points no other point beats in both a and b (both minimised; NaN never on the front).

    Args:
        a: the first objective (n,).
        b: the second objective (n,).

    Returns:
        Boolean mask (n,) of the front.
    """
    ok = np.isfinite(a) & np.isfinite(b)
    mask = np.zeros(len(a), dtype=bool)
    for i in np.flatnonzero(ok):
        dominated = ok & (a <= a[i]) & (b <= b[i]) & ((a < a[i]) | (b < b[i]))
        mask[i] = not dominated.any()
    return mask


def heat_map(
    frame: pd.DataFrame, x: str, y: str, metric: str, path: str | Path, title: str = "", unit: str = ""
) -> Path:
    """The metric over a grid of two parameters (one row per (x, y)); non-ok designs in grey.

    Args:
        frame: the sweep's table.
        x: the parameter along x.
        y: the parameter along y.
        metric: the column drawn.
        path: the file written.
        title: the figure's title (default: the metric).
        unit: the metric's unit, for the colour bar.

    Returns:
        The path written.

    Raises:
        InvalidParameters: a column the table does not have.
    """
    plt = pyplot("sweep plots")

    _columns(frame, x, y, metric)
    xs, ys = np.unique(frame[x]), np.unique(frame[y])
    grid = np.full((len(ys), len(xs)), np.nan)
    for _, row in frame[frame["status"] == "ok"].iterrows():
        grid[np.searchsorted(ys, row[y]), np.searchsorted(xs, row[x])] = row[metric]
    fig, ax = plt.subplots(figsize=(5.6, 4.4))
    ax.set_facecolor("0.8")
    mesh = ax.pcolormesh(xs, ys, np.ma.masked_invalid(grid), shading="nearest", cmap="viridis")
    fig.colorbar(mesh, ax=ax, label=f"{metric} ({unit})" if unit else metric)
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    ax.set_title(title or f"{metric} (grey: not ok)")
    return save_figure(fig, path, dpi=120)


def pareto_plot(
    frame: pd.DataFrame, a: str, b: str, path: str | Path, title: str = "", highlight: dict | None = None
) -> Path:
    """Every ok design in (a, b), its Pareto front (both minimised) joined; `highlight`: label -> (a, b).

    Args:
        frame: the sweep's table.
        a: the first objective's column.
        b: the second objective's column.
        path: the file written.
        title: the figure's title.
        highlight: label -> (a, b) points drawn as stars.

    Returns:
        The path written.

    Raises:
        InvalidParameters: a column the table does not have.
    """
    plt = pyplot("sweep plots")

    _columns(frame, a, b)
    ok = frame[frame["status"] == "ok"]
    va, vb = ok[a].to_numpy(float), ok[b].to_numpy(float)
    front = pareto_mask(va, vb)
    order = np.argsort(va[front])
    fig, ax = plt.subplots(figsize=(5.6, 4.4))
    ax.scatter(va, vb, s=10, color="0.6", label=f"ok designs ({len(ok)} of {len(frame)})")
    ax.plot(va[front][order], vb[front][order], "o-", color="C3", ms=4, label="Pareto front")
    for i, (label, (pa, pb)) in enumerate((highlight or {}).items()):
        ax.plot([pa], [pb], marker="*", ms=14, ls="", color=f"C{i}", label=label)
    ax.set_xlabel(a)
    ax.set_ylabel(b)
    ax.set_title(title or f"{a} vs {b}")
    ax.legend(fontsize=8)
    return save_figure(fig, path, dpi=120)
