"""The tour notebook (docs/notebooks/tour.ipynb) runs top to bottom in a fresh kernel: it loads a
mechanism, shows it inline, runs a motion study, plots efforts and reactions, and checks the motor's
power against the rate of the mechanism's energy (its own assert)."""

from __future__ import annotations

import os

import pytest
from tests_support import ROOT

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")


def test_tour_notebook_runs(monkeypatch):
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])))
    notebook = nbformat.read(ROOT / "docs" / "notebooks" / "tour.ipynb", as_version=4)
    nbclient.NotebookClient(
        notebook, timeout=300, kernel_name="python3", resources={"metadata": {"path": str(ROOT / "docs" / "notebooks")}}
    ).execute()
    outputs = [o for c in notebook.cells if c.cell_type == "code" for o in c.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    html = [o.data["text/html"] for o in outputs if "text/html" in o.get("data", {})]
    assert sum("<iframe srcdoc=" in h for h in html) == 2  # the mechanism as a cell's result, and its scene
    assert any("image/png" in o.get("data", {}) for o in outputs)  # the plot
    text = "".join(o.get("text", "") for o in outputs)
    assert "<Mechanism four_bar: nq=3, dof=1, loops=1, actuators=['crank']>" in text
    assert "worst mismatch" in text
