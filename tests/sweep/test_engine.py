"""`mechkit.sweep.engine`: a sweep on the embedded Dask cluster, its Parquet store, and resuming."""

from __future__ import annotations

import pytest

from mechkit.base.exceptions import InvalidParameters
from mechkit.sweep import DesignSpace, Study, parse_axis, read, sweep


def test_sweep_on_embedded_cluster_and_resume(tmp_path):
    space = DesignSpace((parse_axis("crank=0.06:0.2:4"), parse_axis("ground=0.28:0.40:3")))
    study = Study(law="turn", samples=30)
    out = tmp_path / "r"
    first = sweep("four_bar", space, out, study, workers=1, chunk_size=5)
    frame = read(out)
    assert list(frame["index"]) == list(range(12)) and first.evaluated == 12
    assert first.statuses.get("ok", 0) > 0 and first.statuses.get("singular", 0) > 0
    with pytest.raises(InvalidParameters):  # not overwritten without --resume
        sweep("four_bar", space, out, study, workers=1, chunk_size=5)
    (out / "parts" / "part-000001.parquet").unlink()  # as if killed before that chunk finished
    again = sweep("four_bar", space, out, study, workers=1, chunk_size=5, resume=True)
    assert again.evaluated == 5
    resumed = read(out)
    assert list(resumed["index"]) == list(range(12))
    assert resumed.drop(columns="seconds").equals(frame.drop(columns="seconds"))
    with pytest.raises(InvalidParameters):  # another sweep in the same folder
        sweep("four_bar", space, out, Study(law="turn", samples=31), workers=1, chunk_size=5, resume=True)
