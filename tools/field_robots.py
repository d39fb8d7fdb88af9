"""Regenerate docs/field_robots.md and its snapshots docs/field_robots/*.png: every robot of
`mechkit.bench.field.ROBOTS` through `mechkit report` (its DOF, loops, idle freedoms, holding efforts),
a snapshot of its home (headless Chromium: `apt-get install chromium`) and its warm load time.
`tests/sources/test_field_page.py` loads every robot on the page and checks what it says.

Usage: python tools/field_robots.py
"""

from __future__ import annotations

import re
import sys
import tempfile
from pathlib import Path

from mechkit.base.atomic import write_text
from mechkit.base.exceptions import MechkitError
from mechkit.bench import field
from mechkit.cli.common import assembly_line
from mechkit.report import report
from mechkit.viz.browser import screenshot
from mechkit.viz.pages import snapshot

ROOT = Path(__file__).resolve().parent.parent
FIXTURES = ROOT / "tests" / "fixtures" / "field"
PAGE = ROOT / "docs" / "field_robots.md"
PICTURES = ROOT / "docs" / "field_robots"
SIZE = (480, 360)  # pixels

INTRO = """# Robots from the field

Closed-loop robots as the field publishes them, read by mechkit without editing a file: Gepetto's
example-parallel-robots (Extended URDF: a URDF and a YAML sidecar), MuJoCo Menagerie (MJCF),
example-robot-data's Cassie (SDFormat), the URDF+ authors' example models and Drake's Strandbeest (a
xacro: 12 legs, 36 loops closed by `drake:ball_constraint` or `drake:linear_bushing_rpy`, its crossbar
free as Drake leaves a body no joint holds); then small files of our own (license "ours") closed the way
other tools close loops: Drake's ball constraint and bushing (URDF, SDFormat), Gazebo's
`<gazebo><joint>`, SDFormat written joints first, nested or with universal joints, onshape-to-robot's
closing frames (URDF) and connect equalities by site (MJCF). The fixtures, with their licenses and
source READMEs, are in `tests/fixtures/field/`, `tests/fixtures/drake/`, `tests/fixtures/closures/` and
`tests/fixtures/onshape/` (example-robot-data is a test dependency). Each robot is given as `mechkit
report` gives it: its numerical DOF, its loops, its idle freedoms (a rod spinning about its own axis
between two balls), and the motor efforts holding it still under gravity and its springs, the motors at
home and what they do not drive (springs, idle rods) settled; or why they cannot (a floating pelvis,
fingers resting on their stops, a pose whose passive motion the motors do not determine), and for a file
mechkit refuses, why (in one line). The load time is that of a warm `mechkit.load` (docs/benchmarks.md,
"Loading the field's robots").

`tests/sources/test_field_page.py` loads every robot of this page in CI and checks its row;
`tests/sources/test_field_*.py` check the same reports against independent computations (Pinocchio
alone, MuJoCo's own functions); the Strandbeest's crank torque holding it and the Drake four-bars' are
checked against Drake's plant of the same file (`tests/sources/test_drake_elements.py`, to 1e-8), the
onshape-to-robot MJCF against MuJoCo (`tests/sources/test_onshape_closures.py`), the SDFormat files
against the same linkages built by hand with Pinocchio calls and against Drake's parser
(`tests/sources/test_sdf.py`, `tests/sources/test_sdf_nested.py`). Regenerate with `python
tools/field_robots.py`. In the snapshots, red: actuated joints; dark: passive joints and the bars of
bodies whose file draws nothing (the field's meshes are not copied); magenta: a missing mesh; yellow
spheres: loop cuts. Each section's assembly line says how the home pose was found and which loop joints it
leaves outside their limits: for Drake's Strandbeest and two Gepetto robots (battobot_6d, robot_delta),
Newton from the joints' zero lands on another assembly than their limits mean, and mechkit finds the one
inside them ("re-sought inside the limits": `mechkit.core.seek_inside_limits`); true_talos_2_legs' shins
have none it finds (nor do 200 random starts), so they are named and its holding efforts are that pose's
(the failed search costs its load about 0.45 s).
"""


def slug(label: str) -> str:
    """The snapshot's file stem for a robot label."""
    return re.sub(r"[^a-z0-9]+", "_", label.lower()).strip("_")


def command(robot: field.FieldRobot) -> str:
    """The `mechkit report` command line of a robot (its file as the repository or the environment holds it)."""
    folders = {"fixtures": "tests/fixtures/field/", "tests": "tests/fixtures/"}
    where = folders.get(robot.root, "<example-robot-data>/") + robot.path
    return " ".join(["mechkit report", where, *robot.options()])


def main() -> int:
    PICTURES.mkdir(parents=True, exist_ok=True)
    times = {t.label: t for t in field.load_times(FIXTURES)}
    rows = [
        "| robot | source (license) | DOF | loops | idle freedoms | holding gravity at rest | load (ms) |",
        "|---|---|---|---|---|---|---|",
    ]
    sections = []
    for robot in field.ROBOTS:
        t = times[robot.label]
        source = f"[{robot.source.rsplit('/', 1)[-1]}]({robot.source}) ({robot.license})"
        lines = [f"### {robot.label}", "", f"`{command(robot)}`", ""]
        if t.median_s is None:
            rows.append(f"| {robot.label} | {source} | - | - | - | refused | - |")
            sections += [*lines, f"Refused: {t.refused}", ""]
            continue
        mech = robot.load(FIXTURES)
        r = report(mech)
        held = r["holding"]
        idle = ", ".join(f"{b} {n}" for b, n in r["idle"].items()) or "none"
        kinds = ", ".join(f"{c['name']} ({c['kind']})" for c in r["closures"]) or "none"
        rows.append(
            f"| {robot.label} | {source} | {r['dof']} | {len(r['closures'])} | {idle} | "
            f"{'holds' if 'efforts' in held else 'cannot'} | {t.median_s * 1e3:.1f} |"
        )
        png = PICTURES / f"{slug(robot.label)}.png"
        with tempfile.TemporaryDirectory(prefix="mechkit-field-") as tmp:
            screenshot(write_text(Path(tmp) / "page.html", snapshot(mech)), png, size=SIZE)
        lines += [
            f"![{robot.label}](field_robots/{png.name})",
            "",
            f"- DOF {r['dof']} (Kutzbach count {r['dof_gruebler']}), nv {r['nv']}; loops: {kinds}",
            f"- idle freedoms: {idle}",
            f"- {assembly_line(mech.home_assembly)}",
        ]
        if "efforts" in held:
            efforts = ", ".join(f"{a} {u:.6g}" for a, u in held["efforts"].items())
            lines.append(f"- holding gravity at rest (N m or N): {efforts}")
            if held["settled"]:
                lines.append(f"- with the joints the motors do not drive settled: {', '.join(held['settled'])}")
            if held["undetermined"]:
                lines.append(f"- not fixed by statics (least-norm shares given): {', '.join(held['undetermined'])}")
        else:
            lines.append(f"- holding gravity at rest: the motors cannot: {held['refused']}")
        sections += [*lines, f"- load: {t.median_s * 1e3:.1f} ms", ""]
        print(f"{robot.label}: DOF {r['dof']}, {png.stat().st_size / 1000:.0f} kB")
    write_text(PAGE, "\n".join([INTRO, *rows, "", "## Each robot", "", *sections]))
    print(f"wrote {PAGE.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except MechkitError as err:
        print(f"error: {err}", file=sys.stderr)
        sys.exit(1)
