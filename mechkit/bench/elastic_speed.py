"""Speed of the elastic quantities (issue 24): the compliant reactions batched against the rigid batched
inverse dynamics per sample, the 2T1R's platform stiffness at one pose, and the deployable truss's
first six natural modes; each the fastest of its repeats (the least disturbed on a shared machine).

Targets: compliant / rigid batched at most 3; the 2T1R's platform stiffness under 1 ms; the
deployable's first 6 modes under 50 ms. Multithreaded BLAS on a busy machine of two cores stalls
small LAPACK calls by two orders of magnitude: run with OPENBLAS_NUM_THREADS=1 for stable figures.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechkit.bench.sampling import make_samples
from mechkit.bench.timing import time_per_call
from mechkit.elastic import ElasticModel
from mechkit.loading import load
from mechkit.mechanism import Mechanism

#: Samples per batched call.
BATCH = 32
#: The 2T1R platform's centroid in its frame (m): (0, -2 l1 / 3, 0) at the default l1 = 0.4 m.
PLATFORM_CENTROID = (0.0, -0.8 / 3.0, 0.0)


@dataclass(frozen=True)
class ElasticSpeedRow:
    """One timed quantity: its time (us; per sample for batched rows), the reference time it is
    compared with (us, or nan), and the target it is held to."""

    label: str
    us: float
    reference_us: float
    target: str
    met: bool


def _states(mech: Mechanism) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """`BATCH` states (q, v, a) of the bench's samples near home (`mechkit.bench.sampling`), tiled."""
    samples = make_samples(mech, 8)
    pick = [samples[i % len(samples)] for i in range(BATCH)]
    return np.array([s.q for s in pick]), np.array([s.v for s in pick]), np.array([s.a for s in pick])


def reaction_rows(
    names: tuple[str, ...] = ("four_bar", "parallel_2t1r", "deployable_9rr12uru"),
    budget_s: float = 0.3,
    repeats: int = 5,
) -> list[ElasticSpeedRow]:
    """Compliant against rigid batched inverse dynamics (states near home, moving), us per sample.

    Args:
        names: the registered mechanisms timed.
        budget_s: seconds of timing per call.
        repeats: timed repeats (the minimum is kept).

    Returns:
        One row per mechanism.
    """
    out = []
    for name in names:
        mech = load(name, rows="spatial") if name == "four_bar" else load(name)
        elastic = ElasticModel(mech)
        Q, V, A = _states(mech)
        rigid = time_per_call(
            lambda _, m=mech, s=(Q, V, A): m.inverse_dynamics_batch(*s), [None], budget_s, repeats
        ).min() / len(Q)
        compliant = time_per_call(
            lambda _, e=elastic, s=(Q, V, A): e.inverse_dynamics_batch(*s), [None], budget_s, repeats
        ).min() / len(Q)
        out.append(
            ElasticSpeedRow(
                f"{name}: compliant reactions, batched ({BATCH})",
                compliant * 1e6,
                rigid * 1e6,
                "<= 3 x rigid batched",
                compliant <= 3 * rigid,
            )
        )
    return out


def stiffness_row(budget_s: float = 0.3, repeats: int = 5) -> ElasticSpeedRow:
    """The 2T1R's platform stiffness (6x6, at its centroid) at the home pose.

    Args:
        budget_s: seconds of timing.
        repeats: timed repeats (the minimum is kept).

    Returns:
        The row.
    """
    mech = load("parallel_2t1r")
    elastic = ElasticModel(mech)
    s = time_per_call(
        lambda _: elastic.stiffness(mech.home_q, "platform", PLATFORM_CENTROID), [None], budget_s, repeats
    ).min()
    return ElasticSpeedRow("parallel_2t1r: platform stiffness, one pose", s * 1e6, float("nan"), "< 1000 us", s < 1e-3)


def modes_row(budget_s: float = 0.3, repeats: int = 5) -> ElasticSpeedRow:
    """The deployable truss's first 6 modes at its deployed pose.

    Args:
        budget_s: seconds of timing.
        repeats: timed repeats (the minimum is kept).

    Returns:
        The row.
    """
    mech = load("deployable_9rr12uru")
    elastic = ElasticModel(mech)
    s = time_per_call(lambda _: elastic.modes(mech.home_q, 6), [None], budget_s, repeats).min()
    return ElasticSpeedRow("deployable_9rr12uru: first 6 modes", s * 1e6, float("nan"), "< 50000 us", s < 0.05)


def rows(budget_s: float = 0.3, repeats: int = 5) -> list[ElasticSpeedRow]:
    """Every row of this page section.

    Args:
        budget_s: seconds of timing per call.
        repeats: timed repeats (the minimum is kept).

    Returns:
        The reaction rows, the stiffness row and the modes row.
    """
    return [
        *reaction_rows(budget_s=budget_s, repeats=repeats),
        stiffness_row(budget_s, repeats),
        modes_row(budget_s, repeats),
    ]


def lines(measured: list[ElasticSpeedRow]) -> list[str]:
    """A markdown table of the rows.

    Args:
        measured: what `rows` gave.

    Returns:
        The table's lines.
    """
    table = ["| quantity | us | rigid batched (us/sample) | ratio | target | met |", "|---|---|---|---|---|---|"]
    for r in measured:
        ratio = "" if np.isnan(r.reference_us) else f"{r.us / r.reference_us:.2f}"
        reference = "" if np.isnan(r.reference_us) else f"{r.reference_us:.0f}"
        table.append(f"| {r.label} | {r.us:.0f} | {reference} | {ratio} | {r.target} | {'yes' if r.met else 'no'} |")
    return table
