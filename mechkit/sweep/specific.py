"""The table of every metric a sweep can ask of a mechanism: the generic ones and its own.

A mechanism's own metrics are the figures of merit its spec declares (`MechanismSpec.design_metrics`,
read through the registry: the engine gimbal's `rule_error`, the ten-bar's `deployment`, ...): they
need no motion study. A mechanism that declares some measures "assembles", "branch" and those by
default; any other, every generic metric.
"""

from __future__ import annotations

from mechkit.base.exceptions import InvalidParameters
from mechkit.catalog.contract import DesignMetric
from mechkit.catalog.registry import get_spec
from mechkit.sweep.metrics import ELASTIC, GENERIC, Metric

#: The generic metrics a mechanism with metrics of its own measures by default, before those.
DEFAULT_GENERIC = ("assembles", "branch")


def _metric(declared: DesignMetric) -> Metric:
    """A mechanism's declared figure of merit as a sweep metric (computed without the motion study)."""
    return Metric(
        declared.name,
        declared.unit,
        declared.doc,
        lambda mech: list(declared.columns),
        lambda mech, samples: declared.fn(mech),
        motion=False,
    )


def own(mechanism: str) -> tuple[Metric, ...]:
    """The metrics a registered mechanism declares, as sweep metrics.

    Args:
        mechanism: a registered name.

    Returns:
        Its metrics (none when it declares none).
    """
    return tuple(_metric(d) for d in get_spec(mechanism).design_metrics)


def available(mechanism: str) -> dict[str, Metric]:
    """Every metric of a registered mechanism by name: the generic ones, the elastic ones and its own.

    Args:
        mechanism: a registered name.

    Returns:
        Metric name -> metric.
    """
    return {m.name: m for m in GENERIC + ELASTIC + own(mechanism)}


def resolve(mechanism: str, names: list[str] | tuple[str, ...] | None) -> tuple[Metric, ...]:
    """The metrics asked for (default: "assembles", "branch" and the mechanism's own when it declares
    any, else every generic metric).

    Args:
        mechanism: a registered name.
        names: metric names, or None for the default.

    Returns:
        The metrics, in the order asked (each once).

    Raises:
        InvalidParameters: a name the mechanism does not have.
    """
    known = available(mechanism)
    mine = own(mechanism)
    default = DEFAULT_GENERIC + tuple(m.name for m in mine) if mine else tuple(m.name for m in GENERIC)
    chosen = names or default
    for name in chosen:
        if name not in known:
            raise InvalidParameters("metric", name, f"{mechanism} has the metrics {', '.join(known)}")
    return tuple(known[name] for name in dict.fromkeys(chosen))
