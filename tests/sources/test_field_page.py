"""docs/field_robots.md says what mechkit does with each robot of the field: every robot on it
(`mechkit.bench.field.ROBOTS`, in its order) is loaded here through `mechkit report`, and its row (DOF,
loops, idle freedoms, whether the motors hold) and its holding efforts are what the report gives; a
robot the page says mechkit refuses is refused in one line; each loaded robot has its snapshot."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from mechkit.bench.field import ROBOTS

from .field_cli import refusal, report

DOCS = Path(__file__).resolve().parents[2] / "docs"
FIXTURES = Path(__file__).resolve().parents[1] / "fixtures" / "field"
PAGE = (DOCS / "field_robots.md").read_text()


def _rows() -> dict[str, list[str]]:
    table = PAGE[PAGE.index("| robot |") : PAGE.index("## Each robot")].strip().splitlines()[2:]
    return {cells[0]: cells[1:] for cells in ([c.strip() for c in line.strip("|").split("|")] for line in table)}


def _section(label: str) -> str:
    start = PAGE.index(f"### {label}\n")
    end = PAGE.find("\n### ", start + 1)
    return PAGE[start:] if end < 0 else PAGE[start:end]


def test_the_page_lists_every_robot_in_order():
    assert list(_rows()) == [r.label for r in ROBOTS]


@pytest.mark.parametrize("robot", ROBOTS, ids=[r.label for r in ROBOTS])
def test_each_robot_is_what_the_page_says(robot):
    _, dof, loops, idle, holds, _ = _rows()[robot.label]
    if dof == "-":
        said = re.search(r"Refused: (.*)", _section(robot.label)).group(1)
        assert holds == "refused" and said in refusal(robot.file(FIXTURES), *robot.options())
        return
    r = report(robot.file(FIXTURES), *robot.options())
    assert (int(dof), int(loops)) == (r["dof"], len(r["closures"]))
    assert idle == (", ".join(f"{b} {n}" for b, n in r["idle"].items()) or "none")
    assert holds == ("holds" if "efforts" in r["holding"] else "cannot")
    section = _section(robot.label)
    picture = re.search(r"!\[[^]]*\]\((field_robots/[^)]+\.png)\)", section).group(1)
    assert (DOCS / picture).stat().st_size > 1000
    if "efforts" in r["holding"]:
        shown = re.search(r"holding gravity at rest \(N m or N\): (.*)", section).group(1).split(", ")
        for item, (actuator, effort) in zip(shown, r["holding"]["efforts"].items(), strict=True):
            name, value = item.rsplit(" ", 1)
            assert name == actuator and float(value) == pytest.approx(effort, rel=1e-5, abs=1e-9)
    else:
        assert r["holding"]["refused"] in section
