"""Benchmark rows of the second opinion (`mechkit.second_opinion`): the one-off cost of decomposing a
mechanism, and the per-sample time of its SOC solve next to constrained RNEA (with the determinacy
test, which the second opinion also gives), measured in one run on the same states of its scene."""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass

import numpy as np

from mechkit.bench.timing import time_per_call
from mechkit.catalog.registry import names as registered
from mechkit.loading import load
from mechkit.scenes import SweepStopped
from mechkit.second_opinion.agreement import agreement, scene_states
from mechkit.second_opinion.opinion import SecondOpinion


@dataclass(frozen=True)
class SecondOpinionRow:
    """One mechanism's figures.

    Attributes:
        name: mechanism.
        skcs: SKCs of its decomposition; largest: unknowns of its largest SKC.
        decompose_ms: structure graph + Dulmage-Mendelsohn decomposition, once (ms, best of 3).
        soc_us, rnea_us: per-sample solve time (us, median of the repeats).
        ratio: soc_us / rnea_us.
        samples: states timed and compared; max_relative_difference: agreement over them.
    """

    name: str
    skcs: int
    largest: int
    decompose_ms: float
    soc_us: float
    rnea_us: float
    ratio: float
    samples: int
    max_relative_difference: float


def second_opinion_rows(
    mechanisms: list[str] | None = None,
    samples: int = 6,
    scene: str | None = None,
    budget_s: float = 1.0,
    repeats: int = 3,
) -> list[SecondOpinionRow]:
    """Decomposition cost and per-sample solve times of each mechanism (all registered by default).

    Args:
        mechanisms: registered names (default: all).
        samples: states along the scene (`scene_states`).
        scene: scene to sample (default: each mechanism's first).
        budget_s: timing budget per method, s (`mechkit.bench.timing.time_per_call`).
        repeats: timing repeats (`mechkit.bench.timing.time_per_call`).

    Returns:
        One row per mechanism: SKCs, the largest, decomposition time (ms), SOC and constrained RNEA times (us per
            sample), their ratio and the agreement.
    """
    rows = []
    for name in mechanisms or list(registered()):
        mech = load(name)
        decompose = []
        for _ in range(3):
            start = time.perf_counter()
            opinion = SecondOpinion(mech)
            decompose.append(time.perf_counter() - start)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", SweepStopped)
            states = scene_states(mech, samples, scene=scene)
        soc = float(np.median(time_per_call(lambda s, o=opinion: o.solve(*s), states, budget_s, repeats)))
        rnea = float(np.median(time_per_call(lambda s, m=mech: m.inverse_dynamics(*s), states, budget_s, repeats)))
        agree = agreement(opinion, states, timing=False)
        largest = max(len(s.unknowns) for s in opinion.skcs)
        rows.append(
            SecondOpinionRow(
                name,
                len(opinion.skcs),
                largest,
                min(decompose) * 1e3,
                soc * 1e6,
                rnea * 1e6,
                soc / rnea,
                agree.samples,
                agree.max_relative_difference,
            )
        )
    return rows


def lines(rows: list[SecondOpinionRow]) -> list[str]:
    """A markdown table of the rows.

    Args:
        rows: the rows.

    Returns:
        Markdown lines.
    """
    table = [
        (
            "| mechanism | SKCs | largest SKC (unknowns) | decompose (ms, once) | SOC (us/sample) "
            "| constrained RNEA + determinacy (us/sample) | SOC / RNEA | samples | max rel. difference |"
        ),
        "|---|---|---|---|---|---|---|---|---|",
    ]
    table += [
        f"| {r.name} | {r.skcs} | {r.largest} | {r.decompose_ms:.0f} | {r.soc_us:.0f} | {r.rnea_us:.0f} "
        f"| {r.ratio:.1f} | {r.samples} | {r.max_relative_difference:.1e} |"
        for r in rows
    ]
    return table
