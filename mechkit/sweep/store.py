"""The results of a sweep on disk: a Parquet dataset, one row per design, written chunk by chunk.

Layout of the results folder:

- `sweep.json`: the manifest (mechanism, fixed parameters, design space, study, metrics, columns,
  chunk size, number of designs); a resumed sweep must match it.
- `designs.parquet`: every design's index and parameter values, written before any is evaluated.
- `parts/part-NNNNNN.parquet`: the rows of chunk NNNNNN (designs chunk*size .. (chunk+1)*size - 1),
  each written atomically (a temporary file, then a rename) once the whole chunk is done.

A killed sweep leaves only whole part files, so `--resume` evaluates exactly the chunks without one:
no design is lost and none is evaluated twice.
"""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

from mechkit.base.atomic import write_bytes, write_text
from mechkit.base.exceptions import InvalidParameters, MalformedDescription

if TYPE_CHECKING:
    import pandas as pd

MANIFEST = "sweep.json"
DESIGNS = "designs.parquet"
PARTS = "parts"
_PART = re.compile(r"part-(\d{6})\.parquet")


def schema(names: tuple[str, ...], columns: tuple[str, ...]) -> pa.Schema:
    """Row schema: index, the swept parameters, the metric columns, status, message, seconds.

    Args:
        names: the swept parameters.
        columns: the metric columns.

    Returns:
        The pyarrow schema.
    """
    fields = [pa.field("index", pa.int64())]
    fields += [pa.field(n, pa.float64()) for n in (*names, *columns)]
    fields += [pa.field("status", pa.string()), pa.field("message", pa.string()), pa.field("seconds", pa.float64())]
    return pa.schema(fields)


def _bytes(table: pa.Table) -> bytes:
    sink = pa.BufferOutputStream()
    pq.write_table(table, sink)
    return sink.getvalue().to_pybytes()


def prepare(out: Path, manifest: dict, designs: np.ndarray, resume: bool) -> set[int]:
    """Create the results folder (or check it against the manifest when resuming); the chunks done.

    Args:
        out: the results folder.
        manifest: what the sweep is (mechanism, space, study, metrics, ...).
        designs: the designs (n, parameters).
        resume: continue the sweep the folder holds.

    Returns:
        The chunks already done (empty for a new sweep).

    Raises:
        InvalidParameters: the folder holds a sweep and `resume` is False, or it holds another sweep.
    """
    out = Path(out)
    existing = out / MANIFEST
    if existing.exists():
        if not resume:
            raise InvalidParameters(
                "output", str(out), "already holds a sweep: pass --resume to continue it, or choose another folder"
            )
        found = json.loads(existing.read_text())
        if found != manifest:
            changed = sorted(k for k in manifest if found.get(k) != manifest[k])
            raise InvalidParameters("output", str(out), f"holds a different sweep (differs in {', '.join(changed)})")
        return done_chunks(out)
    if out.exists() and any(out.iterdir()):
        raise InvalidParameters("output", str(out), "is not empty and holds no sweep")
    names = [a[0] for a in manifest["space"]["axes"]]
    table = pa.table(
        {
            "index": pa.array(np.arange(len(designs)), pa.int64()),
            **{n: pa.array(designs[:, i], pa.float64()) for i, n in enumerate(names)},
        }
    )
    write_bytes(out / DESIGNS, _bytes(table))
    (out / PARTS).mkdir(parents=True, exist_ok=True)
    write_text(existing, json.dumps(manifest, indent=1, sort_keys=True))
    return set()


def read_manifest(out: Path) -> dict:
    """The manifest of the sweep in `out`.

    Args:
        out: the results folder.

    Returns:
        The manifest.

    Raises:
        InvalidParameters: no sweep there.
    """
    path = Path(out) / MANIFEST
    if not path.exists():
        raise InvalidParameters("output", str(out), "holds no sweep (no sweep.json)")
    return json.loads(path.read_text())


def done_chunks(out: Path) -> set[int]:
    """Chunk numbers whose part file exists.

    Args:
        out: the results folder.

    Returns:
        The chunk numbers.
    """
    parts = Path(out) / PARTS
    return {int(m.group(1)) for p in parts.iterdir() if (m := _PART.fullmatch(p.name))} if parts.exists() else set()


def write_part(out: Path, chunk: int, rows: list[dict], row_schema: pa.Schema) -> Path:
    """Write one finished chunk's rows atomically.

    Args:
        out: the results folder.
        chunk: the chunk's number.
        rows: its rows (`evaluate_chunk`).
        row_schema: the table's schema.

    Returns:
        The part file written.
    """
    table = pa.Table.from_pylist(rows, schema=row_schema)
    return write_bytes(Path(out) / PARTS / f"part-{chunk:06d}.parquet", _bytes(table))


def read(out: Path) -> pd.DataFrame:
    """Every row written so far, as a pandas DataFrame sorted by design index.

    Args:
        out: the results folder.

    Returns:
        The rows.

    Raises:
        MalformedDescription: a design appears twice.
        InvalidParameters: no sweep there.
    """
    parts = sorted((Path(out) / PARTS).glob("part-*.parquet"))
    manifest = read_manifest(out)
    row_schema = schema(tuple(a[0] for a in manifest["space"]["axes"]), tuple(manifest["columns"]))
    if not parts:
        return row_schema.empty_table().to_pandas()
    frame = pa.concat_tables([pq.read_table(p, schema=row_schema) for p in parts]).to_pandas()
    if frame["index"].duplicated().any():
        raise MalformedDescription(str(out), "a design index appears in two part files")
    return frame.sort_values("index").reset_index(drop=True)
