"""`mechkit.bench.field`: the section of docs/benchmarks.md that `tools/bench_all.py --speed` writes, put
before "## First load", replaced (not repeated) when written again, the rest of the page untouched; a
refused robot shows its reason, the others their size and a load time."""

from __future__ import annotations

from pathlib import Path

from mechkit.bench.field import ROBOTS, SECTION, add_section

FIXTURES = Path(__file__).resolve().parents[1] / "fixtures" / "field"


def test_the_section_goes_before_the_first_load_and_is_replaced_when_written_again(tmp_path):
    page = tmp_path / "benchmarks.md"
    page.write_text("# Benchmarks\n\n## Second opinion\n\nrows\n\n## First load\n\nmore\n")
    robots = tuple(r for r in ROBOTS if r.label in ("urdf+ four_bar", "disney_robot"))
    for _ in range(2):
        add_section(page, FIXTURES, quick=True, robots=robots)
        text = page.read_text()
        assert text.count(f"## {SECTION}") == 1
        assert text.index("## Second opinion") < text.index(f"## {SECTION}") < text.index("## First load")
        assert text.endswith("## First load\n\nmore\n")
    rows = {line.split(" | ")[0].strip("| "): line for line in text.splitlines() if line.startswith("| ")}
    assert rows["urdf+ four_bar"].startswith("| urdf+ four_bar | 3 | 1 | ")
    assert "refused: gepetto/disney_robot/robot.yaml: joint_name: 'left_spherical_free_foot'" in rows["disney_robot"]
