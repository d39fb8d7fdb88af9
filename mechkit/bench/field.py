"""The field's robots: the files of docs/field_robots.md and the time `mechkit.load` takes on each.

`ROBOTS` lists them (`FieldRobot`): a label, the file (under the repository's `tests/fixtures/field` or
`tests/fixtures`, or in example-robot-data, a test dependency), the bodies `mechkit.load` fixes (a floating pelvis),
where the file comes from and its license. `load_times` times `mechkit.load` of each in one process,
warm (after one untimed load: imports and caches are warm; the reader parses and checks the file, the
core analyses it and assembles its home every time), the median of `repeats`; a file mechkit refuses
gets its one-line reason instead. `lines` is their markdown table, the section `SECTION` of
docs/benchmarks.md, which `add_section` writes there (`tools/bench_all.py --speed` calls it).
"""

from __future__ import annotations

import sysconfig
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mechkit.base.exceptions import MechkitError
from mechkit.loading import load
from mechkit.mechanism import Mechanism

SECTION = "Loading the field's robots"
GEPETTO = ("https://github.com/Gepetto/example-parallel-robots", "BSD-3-Clause")
MENAGERIE = "https://github.com/google-deepmind/mujoco_menagerie"
ERD = ("https://github.com/Gepetto/example-robot-data", "BSD-3-Clause; upstream DAIRLab/cassie-gazebo-sim, ISC")
URDF_PLUS = ("https://github.com/ROAM-Lab-ND/generalized_rbda", "MIT")
DRAKE = "https://github.com/RobotLocomotion/drake"
GAZEBO = "https://github.com/gazebosim/sdformat"
ONSHAPE = "https://github.com/Rhoban/onshape-to-robot"
#: The license column of our own files written in another tool's convention.
OURS = "ours, BSD-3-Clause"


@dataclass(frozen=True)
class FieldRobot:
    """One robot of the page.

    Attributes:
        label: its name on the page (unique).
        path: its file, relative to `root`'s folder.
        root: "fixtures" (the repository's tests/fixtures/field), "tests" (its tests/fixtures: the
            closures other tools write) or "example-robot-data" (its robots folder in this environment).
        fix: bodies `mechkit.load` fixes (`fix=`, the command line's --fix).
        actuated: the joints driven where the file declares no actuator (`actuated=`, --actuated).
        source: the repository the file comes from (URL); license: its license.
    """

    label: str
    path: str
    root: str
    fix: tuple[str, ...] = ()
    source: str = ""
    license: str = ""
    actuated: tuple[str, ...] = ()

    def file(self, fixtures: Path) -> Path:
        """The robot's file.

        Args:
            fixtures: the repository's tests/fixtures/field folder.

        Returns:
            The path of its file (under `fixtures` or example-robot-data's).
        """
        folders = {"fixtures": fixtures, "tests": fixtures.parent}
        return (folders[self.root] if self.root in folders else example_robot_data()) / self.path

    def options(self) -> list[str]:
        """Its options on the command line (`--fix BODY` each, `--actuated J1,J2`)."""
        actuated = ["--actuated", ",".join(self.actuated)] if self.actuated else []
        return [arg for body in self.fix for arg in ("--fix", body)] + actuated

    def load(self, fixtures: Path) -> Mechanism:
        """The robot as `mechkit.load` reads it with its options.

        Args:
            fixtures: the repository's tests/fixtures/field folder.

        Returns:
            The mechanism.

        Raises:
            MechkitError: what `mechkit.load` refuses.
        """
        return load(self.file(fixtures), fix=list(self.fix) or None, actuated=list(self.actuated) or None)


def example_robot_data() -> Path:
    """example-robot-data's robots folder in this environment (its cmeel prefix)."""
    return Path(sysconfig.get_paths()["purelib"], "cmeel.prefix", "share", "example-robot-data", "robots")


_GEPETTO_ROBOTS = (
    "5bar_linkage",
    "5bar_linkage_iso3d",
    "5bar_linkage_iso6d",
    "battobot_6d",
    "cassie_like",
    "digit_like",
    "digit_like_2legs",
    "digit_like_2legs_6D",
    "digit_like_2legs_old",
    "disney_like",
    "disney_robot",
    "kangaroo_like",
    "kangaroo_like_2legs",
    "robot_delta",
    "talos_like",
    "wl16_like",
)
_CASSIE_SDF = "cassie_description/robots/"
_BEEST = "drake/strandbeest/Strandbeest"
#: The robots of docs/field_robots.md.
ROBOTS: tuple[FieldRobot, ...] = (
    *(FieldRobot(r, f"gepetto/{r}/robot.urdf", "fixtures", (), *GEPETTO) for r in _GEPETTO_ROBOTS),
    FieldRobot("true_talos_2_legs", "gepetto/true_talos_2_legs/talos_full_v2.urdf", "fixtures", (), *GEPETTO),
    FieldRobot("menagerie cassie", "menagerie/agility_cassie/cassie.xml", "fixtures", (), MENAGERIE, "MIT"),
    FieldRobot(
        "menagerie cassie, pelvis fixed",
        "menagerie/agility_cassie/cassie.xml",
        "fixtures",
        ("cassie-pelvis",),
        MENAGERIE,
        "MIT",
    ),
    FieldRobot("menagerie robotiq 2f85", "menagerie/robotiq_2f85/2f85.xml", "fixtures", (), MENAGERIE, "BSD-2-Clause"),
    FieldRobot(
        "menagerie ufactory xarm hand", "menagerie/ufactory_xarm7/hand.xml", "fixtures", (), MENAGERIE, "BSD-3-Clause"
    ),
    *(
        FieldRobot(f"cassie sdf {f}", _CASSIE_SDF + f"{f}.sdf", "example-robot-data", (), *ERD)
        for f in ("cassie", "cassie_v2", "cassie_reduced", "cassie_simple", "cassie_wo_gearbox_spring")
    ),
    FieldRobot("cassie sdf cassie, pelvis fixed", _CASSIE_SDF + "cassie.sdf", "example-robot-data", ("pelvis",), *ERD),
    *(
        FieldRobot(f"urdf+ {f}", f"urdf_plus/{f}.urdf", "fixtures", (), *URDF_PLUS)
        for f in (
            "four_bar",
            "six_bar",
            "mit_humanoid",
            "mit_humanoid_leg",
            "revolute_rotor_chain",
            "planar_leg_linkage",
            "mini_cheetah_leg",
        )
    ),
    FieldRobot(
        "drake strandbeest (ball constraints)", f"{_BEEST}Constraints.urdf.xacro", "tests", (), DRAKE, "BSD-3-Clause"
    ),
    FieldRobot(
        "drake strandbeest (ball constraints), crossbar fixed",
        f"{_BEEST}Constraints.urdf.xacro",
        "tests",
        ("crossbar",),
        DRAKE,
        "BSD-3-Clause",
    ),
    FieldRobot(
        "drake strandbeest (bushings), crossbar fixed",
        f"{_BEEST}Bushings.urdf.xacro",
        "tests",
        ("crossbar",),
        DRAKE,
        "BSD-3-Clause",
    ),
    FieldRobot(
        "drake four-bar (ball constraint, URDF)",
        "closures/four_bar_drake_ball.urdf",
        "tests",
        (),
        DRAKE,
        OURS,
        ("crank",),
    ),
    FieldRobot(
        "drake four-bar (ball constraint, SDFormat)", "closures/four_bar_drake_ball.sdf", "tests", (), DRAKE, OURS
    ),
    FieldRobot(
        "drake four-bar (bushing, URDF)", "closures/four_bar_drake_bushing.urdf", "tests", (), DRAKE, OURS, ("crank",)
    ),
    FieldRobot(
        "gazebo four-bar (gazebo joint)", "closures/four_bar_gazebo_joint.urdf", "tests", (), GAZEBO, OURS, ("crank",)
    ),
    *(
        FieldRobot(f"sdformat {f}", f"sdf/{f}.sdf", "fixtures", (), GAZEBO, OURS, actuated)
        for f, actuated in (
            ("four_bar_gearbox", ()),
            ("four_bar_nested", ("crank_joint",)),
            ("rssr_universal", ("crank_joint",)),
        )
    ),
    FieldRobot("onshape-to-robot four-bar (URDF)", "onshape/four_bar.urdf", "tests", (), ONSHAPE, OURS, ("crank",)),
    FieldRobot("onshape-to-robot four-bar (MJCF)", "onshape/four_bar.xml", "tests", (), ONSHAPE, OURS),
)


@dataclass(frozen=True)
class LoadTime:
    """Warm load time of one robot.

    Attributes:
        label: the robot's. nv, loops: its velocity coordinates and cuts (None: refused).
        median_s: median wall time (s) of `mechkit.load` (None: refused); refused: the reason (files named
            relative to the fixtures folder), else "".
    """

    label: str
    nv: int | None
    loops: int | None
    median_s: float | None
    refused: str = ""


def load_times(fixtures: Path, repeats: int = 7, robots: tuple[FieldRobot, ...] = ROBOTS) -> list[LoadTime]:
    """Median warm load times (see the module docstring).

    Args:
        fixtures: the repository's tests/fixtures/field folder.
        repeats: timed loads per robot.
        robots: the robots timed.

    Returns:
        One row per robot: its median (s), or why mechkit refuses its file.
    """
    out = []
    for robot in robots:
        try:
            mech = robot.load(fixtures)  # untimed: imports, caches
        except MechkitError as err:
            out.append(LoadTime(robot.label, None, None, None, str(err).replace(f"{fixtures}/", "")))
            continue
        samples = []
        for _ in range(repeats):
            start = time.perf_counter()
            robot.load(fixtures)
            samples.append(time.perf_counter() - start)
        out.append(LoadTime(robot.label, mech.model.nv, len(mech.closures), float(np.median(samples))))
    return out


def lines(rows: list[LoadTime]) -> list[str]:
    """A markdown table of the rows (refused files with the start of their reason).

    Args:
        rows: what `load_times` gave.

    Returns:
        The table's lines.
    """
    table = ["| robot | nv | loops | median load (ms) |", "|---|---|---|---|"]
    for r in rows:
        if r.median_s is None:
            table.append(f"| {r.label} | - | - | refused: {r.refused[:90]}{'...' if len(r.refused) > 90 else ''} |")
        else:
            table.append(f"| {r.label} | {r.nv} | {r.loops} | {r.median_s * 1e3:.1f} |")
    return table


def add_section(page: Path, fixtures: Path, quick: bool = False, robots: tuple[FieldRobot, ...] = ROBOTS) -> None:
    """Measure `load_times` of `robots` and write them as the section `SECTION` of the benchmark page:
    in place of the section of that title, else before "## First load", else at the end; the rest of the
    page is left as it is.

    Args:
        page: the benchmark page (markdown), rewritten in place.
        fixtures: the repository's tests/fixtures/field folder.
        quick: 3 repeats per robot instead of 15.
        robots: the robots timed.
    """
    repeats = 3 if quick else 15
    body = [
        f"## {SECTION}",
        "",
        (
            f"`mechkit.load` of each robot of docs/field_robots.md, warm (after one untimed "
            f"load), median of {repeats} in one process: the reader parses and checks the file, "
            "the core analyses it and assembles its home every time. A file mechkit refuses "
            "shows the start of its reason."
        ),
        "",
        *lines(load_times(fixtures, repeats, robots)),
        "",
    ]
    text = page.read_text().split("\n")
    heads = [i for i, line in enumerate(text) if line.startswith("## ")]
    mine = next((i for i in heads if text[i] == f"## {SECTION}"), None)
    if mine is not None:
        end = next((i for i in heads if i > mine), len(text))
        text[mine:end] = body
    else:
        at = next((i for i in heads if text[i] == "## First load"), len(text))
        text[at:at] = body
    page.write_text("\n".join(text))
