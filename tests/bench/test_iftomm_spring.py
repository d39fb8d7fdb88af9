"""`mechkit.bench.iftomm_spring`: the four-bar with a diagonal spring measured against its closed form, and
its section written into a copy of the page without touching the rest."""

from __future__ import annotations

import numpy as np

from mechkit.bench import iftomm_spring


def test_measured_answer_equals_the_closed_form():
    r = iftomm_spring.measure(repeats=1)
    assert abs(r.phi - r.phi_exact) < 1e-12 and abs(r.phi - iftomm_spring.PUBLISHED_PHI) < 5e-11
    assert r.eigenvalue_error < 1e-8 and r.residual < 1e-10 and r.cpu > 0
    assert np.all(r.eigenvalues.real < 0)  # the damper takes energy out of the one mode


def test_section_is_written_in_place(tmp_path):
    page = tmp_path / "iftomm_benchmarks.md"
    page.write_text(f"# Page\n\n{iftomm_spring.HEADING}\n\nold\n\n## Measured\n\nkept\n")
    r = iftomm_spring.write_section(tmp_path)
    text = page.read_text()
    assert "old" not in text and "kept" in text and f"{r.phi_exact:.12f}" in text
