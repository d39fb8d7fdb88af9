"""Figures of the automatic SOC decomposition (docs/second_opinion.md): for every built-in mechanism,
its SKCs as a graph in solve order (left to right), an arrow from the SKC that solves a joint's
reaction or effort to each later SKC that takes it as a known load, labelled with the joint.

Usage: python tools/second_opinion_figures.py [NAME ...]  ->  docs/figures/second_opinion_<name>.png
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import mechkit
from mechkit.catalog.registry import names
from mechkit.second_opinion.opinion import SecondOpinion

OUT = Path(__file__).resolve().parent.parent / "docs" / "figures"
COLOURS = {"determined": "#cfe3f7", "under": "#f9d9b0", "over": "#f4c2c2"}


def _label(i: int, skc) -> str:
    bodies = list(skc.bodies)
    shown = ", ".join(bodies[:3]) + (f", ... (+{len(bodies) - 3})" if len(bodies) > 3 else "")
    extra = len(skc.unknowns) - skc.equations
    lines = [
        f"SKC{i} [{skc.kind}]",
        shown,
        f"{len(skc.unknowns)} unknowns, {len(skc.rows)} rows, "
        f"{skc.equations} independent" + (f" ({extra} indet.)" if extra > 0 else ""),
    ]
    if skc.actuators:
        lines.append("motors: " + ", ".join(skc.actuators))
    if skc.released:
        lines.append("released: " + ", ".join(skc.released[:4]) + (" ..." if len(skc.released) > 4 else ""))
    return "\n".join(lines)


def figure(name: str) -> Path:
    """Draw one mechanism's decomposition; returns the PNG path."""
    opinion = SecondOpinion(mechkit.load(name))
    skcs = opinion.skcs
    solved_in: dict[str, int] = {}
    edges: dict[tuple[int, int], list[str]] = {}
    for i, s in enumerate(skcs):
        for joint in {n for n, _ in s.unknowns}:
            solved_in.setdefault(joint, i)
    for i, plan in enumerate(opinion.plans):
        for joint in plan.known:
            edges.setdefault((solved_in[joint], i), []).append(joint)
    n = len(skcs)
    span = max((b - a for a, b in edges), default=1)
    fig, ax = plt.subplots(figsize=(max(4.2 * n, 6.0), 2.6 + 0.5 * span))
    xs = [4.2 * i for i in range(n)]
    for (a, b), joints in sorted(edges.items()):
        rad = 0.0 if b == a + 1 else -0.35
        ax.annotate(
            "",
            xy=(xs[b] - 1.7, 0),
            xytext=(xs[a] + 1.7, 0),
            arrowprops={"arrowstyle": "->", "color": "#555", "connectionstyle": f"arc3,rad={rad}"},
        )
        text = ", ".join(sorted(joints)[:3]) + (" ..." if len(joints) > 3 else "")
        ax.text(
            (xs[a] + xs[b]) / 2,
            0.55 + (0.0 if b == a + 1 else 0.5 + 0.15 * (b - a)),
            text,
            ha="center",
            fontsize=7,
            color="#333",
        )
    for i, s in enumerate(skcs):
        ax.text(
            xs[i],
            0,
            _label(i + 1, s),
            ha="center",
            va="center",
            fontsize=7.5,
            bbox={"boxstyle": "round,pad=0.4", "fc": COLOURS[s.kind], "ec": "#333"},
        )
    ax.set_xlim(-2.2, xs[-1] + 2.2)
    span = max((b - a for a, b in edges), default=1)
    ax.set_ylim(-1.2, 1.4 + 0.6 * span)
    ax.axis("off")
    ax.set_title(
        f"{name}: automatic SOC decomposition, solve order left to right (arrows: reactions passed on as known loads)",
        fontsize=9,
    )
    path = OUT / f"second_opinion_{name}.png"
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return path


def main(argv: list[str]) -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    for name in argv or list(names()):
        print(figure(name))


if __name__ == "__main__":
    main(sys.argv[1:])
