"""What the bench measured: one `Row` per method, one `MechanismBench` per mechanism."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from mechkit.bench.methods import Method
from mechkit.bench.sampling import Sample


@dataclass
class Row:
    """The measurement of one method on one mechanism.

    Attributes:
        median_s, p25_s, p75_s: time per call (s), median and quartiles over repeats.
        error: the worst error over the samples (see `mechkit.bench.errors`).
        outcome: "ok", "non-finite result" or "raises <exception>: <message>".
        note: what was compared when not everything was ("efforts only", "2/3 reactions").
        x_fastest: time / time of the fastest method of equal or better accuracy.
        x_base: time / time of the quantity's baseline (`mechkit.bench.methods.BASELINES`).
    """

    mechanism: str
    method: Method
    median_s: float = float("nan")
    p25_s: float = float("nan")
    p75_s: float = float("nan")
    error: float = float("nan")
    outcome: str = "ok"
    note: str = ""
    x_fastest: float = float("nan")
    x_base: float = float("nan")


@dataclass
class MechanismBench:
    """All rows of one mechanism, with its references and size.

    Attributes:
        nv: tree velocity coordinates.
        rows_closure: closure rows.
        references: quantity (and "peers") -> the reference's label (or the peers' notes).
        paired: the goals' time ratios timed back to back (`mechkit.bench.run.GOAL_PAIRS`).
        mech, samples: the mechanism and its states, to time again (`mechkit.bench.scale`).
    """

    name: str
    nv: int
    rows_closure: int
    references: dict[str, str]
    rows: list[Row]
    paired: dict[str, float] = field(default_factory=dict)
    mech: Any = None
    samples: list[Sample] = field(default_factory=list)
