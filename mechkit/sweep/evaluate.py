"""One design -> one result row, and one chunk of designs -> its rows (what a Dask task runs).

A task carries everything it needs (`Chunk`): workers keep no state between tasks. Within a chunk the
template is expanded once (`mechkit.sources.template_cache`) and every design substitutes its parameters.
A design that fails is a row with its status and message, never an exception:

- "ok": built, assembled and measured;
- "does_not_assemble": its loops do not close at the home inputs;
- "singular": it assembles at home, but the motion reaches a pose where the inputs do not determine
  the motion (a singular passive block, or the edge of the workspace: a dead point);
- "failed": measured, but a metric has no finite value (a direction held rigidly has no finite stiffness):
  the columns are named in the message, and the values are left NaN rather than passed off as measured;
- "error": anything else (invalid parameters, a numerical failure), with the exception's message.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import ClosureNotConverged, SingularConfiguration
from mechkit.catalog.registry import get_spec
from mechkit.loading import from_expanded
from mechkit.sources.template_cache import TemplateCache
from mechkit.sources.xacro_file import render_urdf
from mechkit.sweep.metrics import SingularAlongMotion, Study, motion_samples
from mechkit.sweep.specific import resolve

STATUSES = ("ok", "does_not_assemble", "singular", "failed", "error")


@dataclass(frozen=True)
class Chunk:
    """The designs of one task.

    Attributes:
        mechanism: registry name.
        base: fixed parameter overrides (name -> value) of every design.
        names: the swept parameters, in the order of `values`' columns.
        indices: (k,) design indices (the rows' keys).
        values: (k, len(names)) parameter values, SI.
        study: the motion study.
        metrics: metric names.
        columns: every metric column, in order (a failed design leaves them NaN).
        fast: build through the template cache (else through xacro for each design).
    """

    mechanism: str
    base: dict
    names: tuple[str, ...]
    indices: tuple[int, ...]
    values: np.ndarray
    study: Study
    metrics: tuple[str, ...]
    columns: tuple[str, ...]
    fast: bool = True


def _status(err: Exception, assembled: bool) -> str:
    if isinstance(err, SingularAlongMotion):
        return "singular"
    if isinstance(err, (ClosureNotConverged, SingularConfiguration)):
        return "singular" if assembled else "does_not_assemble"
    return "error"


def _judged(values: dict[str, float]) -> dict[str, str]:
    """The status and message of a measured design: "failed" naming the metric columns without a finite value."""
    missing = [c for c, v in values.items() if not np.isfinite(v)]
    if missing:
        return {"status": "failed", "message": f"no finite value of {', '.join(missing)}"}
    return {"status": "ok", "message": ""}


def evaluate_chunk(chunk: Chunk) -> list[dict]:
    """Evaluate a chunk's designs (on a worker); a design that fails is a row with its status and
    message, not an error.

    Args:
        chunk: the designs and what to compute of them.

    Returns:
        The rows, in index order: index, parameters, metric columns, status, message, seconds (the design's wall
            time).
    """
    spec = get_spec(chunk.mechanism)
    metrics = resolve(chunk.mechanism, chunk.metrics)
    cache = TemplateCache(spec.template_path) if chunk.fast else None
    rows = []
    for index, values in zip(chunk.indices, chunk.values):
        start = time.perf_counter()
        row: dict = {"index": int(index), **dict(zip(chunk.names, map(float, values)))}
        row.update(dict.fromkeys(chunk.columns, float("nan")))
        assembled = False
        try:
            params = spec.params.from_overrides(**chunk.base, **dict(zip(chunk.names, map(float, values))))
            args = params.xacro_args()
            urdf = cache.render(args) if cache is not None else render_urdf(spec.template_path, args)
            mech = from_expanded(spec, params, urdf)
            assembled = True
            samples = motion_samples(mech, chunk.study) if any(m.motion for m in metrics) else None
            for metric in metrics:
                row.update(metric.fn(mech, samples))
            row.update(_judged({c: row[c] for c in chunk.columns}))
        except Exception as err:  # noqa: BLE001 - every failure is a row; the status says which kind
            row.update(status=_status(err, assembled), message=f"{type(err).__name__}: {err}")
        row["seconds"] = time.perf_counter() - start
        rows.append(row)
    return rows
