"""The reactions page: one table per mechanism and state, Drake's tree column at round-off."""

from __future__ import annotations

import pytest

from mechkit.bench import reactions_page

pytest.importorskip("pydrake", reason="Drake not installed: pip install 'mechkit[peers]'")
pytest.importorskip("mujoco", reason="MuJoCo not installed: pip install 'mechkit[peers]'")


def test_four_bar_section_has_every_joint_and_round_off_drake_tree(load_cached, tmp_path):
    m = load_cached("four_bar")
    page = tmp_path / "r.md"
    reactions_page.write(page, {"four_bar": m})
    text = page.read_text()
    rows = [line for line in text.splitlines() if line.startswith(("| crank ", "| rocker "))]
    assert "### static" in text and "### moving" in text and len(rows) == 4
    for row in rows:
        tree, sap, mj = (float(c) for c in row.strip("|").split("|")[-3:])
        assert tree < 1e-12 < sap < mj
