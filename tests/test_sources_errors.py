"""Bad description files: a one-line named error, nothing written, never a silently different mechanism."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

import mechkit
from mechkit.base.exceptions import InvalidParameters, MalformedDescription

FIXTURES = Path(__file__).parent / "fixtures"
SLIDER = (FIXTURES / "slider_crank.urdf").read_text()
LOOP = '<mechkit:loop name="pin" type="revolute" frame_a="rod_tip" frame_b="slider_pin" axis="0 -1 0"/>'


def _urdf(tmp_path: Path, text: str, name: str = "bad.urdf") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


URDF_CASES = {
    "mistyped namespace URI": (SLIDER.replace('xmlns:mechkit="https://mechkit.dev/loop"', 'xmlns:mechkit="https://mechkit.dev/loops"'),
                               "mechkit.dev/loops"),
    "unknown element of the loop namespace": (SLIDER.replace("<mechkit:loop ", "<mechkit:closure "), "mechkit:closure"),
    "loop outside the namespace": (SLIDER.replace("<mechkit:loop ", "<loop "), "<loop>"),
    "loop frame that does not exist": (SLIDER.replace('frame_b="slider_pin"', 'frame_b="slider_pn"'), "slider_pn"),
    "both frames on one body": (SLIDER.replace('frame_b="slider_pin"', 'frame_b="rod_link"'), "one body"),
    "same frame twice": (SLIDER.replace('frame_b="slider_pin"', 'frame_b="rod_tip"'), "same link"),
    "cycle in the tree": (SLIDER.replace('<parent link="ground"/><child link="crank_link"/>',
                                         '<parent link="slider_link"/><child link="crank_link"/>')
                          .replace('<parent link="ground"/><child link="slider_link"/>', '<parent link="rod_link"/><child link="slider_link"/>'),
                          "cycle"),
    "link with two parents": (SLIDER.replace('<parent link="ground"/><child link="slider_link"/>',
                                             '<parent link="ground"/><child link="rod_link"/>'), "two parent joints"),
    "negative mass": (SLIDER.replace('<mass value="0.4"/>', '<mass value="-1"/>'), "mass -1"),
    "inertia not positive definite": (SLIDER.replace('ixx="2e-5"', 'ixx="-2e-5"'), "positive semi-definite"),
    "home of an unknown joint": (SLIDER.replace('<mechkit:home joint="crank"', '<mechkit:home joint="crnk"'), "crnk"),
    "transmission of an unknown joint": (SLIDER.replace('<joint name="crank"><hardwareInterface>', '<joint name="crnk"><hardwareInterface>'),
                                         "crnk"),
    "not XML": ("this is not a URDF", "not well-formed"),
    "empty": ("   \n", "empty"),
}


@pytest.mark.parametrize("case", list(URDF_CASES))
def test_bad_urdf_is_a_named_error(case, tmp_path):
    text, needle = URDF_CASES[case]
    with pytest.raises(MalformedDescription, match=needle.replace("(", r"\(")):
        mechkit.load(_urdf(tmp_path, text))


def test_without_the_namespace_fix_the_loop_would_be_an_open_tree(tmp_path):
    """The reason the mistyped namespace is an error: the same file without its loop has mobility 3."""
    m = mechkit.load(_urdf(tmp_path, SLIDER.replace(LOOP, "")))
    assert m.mobility().dof == 3


def test_paths_that_are_not_files(tmp_path):
    with pytest.raises(MalformedDescription, match="no such file"):
        mechkit.load(tmp_path / "missing.urdf")
    with pytest.raises(MalformedDescription, match="directory"):
        mechkit.load(tmp_path)
    with pytest.raises(MalformedDescription, match="unknown format"):
        mechkit.load(_urdf(tmp_path, SLIDER, "linkage.txt"))
    with pytest.raises(InvalidParameters, match="no such mechanism"):
        mechkit.load("slider_crank")


def test_sidecar_errors(tmp_path):
    tree = (FIXTURES / "leg.urdf").read_text()
    cases = {
        "closed_loop: [[rod1_tip, shank_levr]]\ntype: [3d]\nname_mot: [hip]\n": "shank_levr",
        "closed_loop: [[rod1_tip, shank_lever]]\ntype: [3d]\nname_mot: [hip, kne]\n": "kne",
        "closed_loop: [[rod1_tip, shank_lever]]\ntype: [4d]\nname_mot: [hip]\n": "4d",
        "closed_loop: [[rod1_tip, shank_lever]]\ntype: [3d, 6d]\nname_mot: [hip]\n": "one type per",
        "closed_loop: [[rod1_tip, rod1]]\ntype: [3d]\nname_mot: [hip]\n": "one body",
        "closed_loop: [rod1_tip\n": "not YAML",
        "name_mot: [hip]\n": "closed_loop",
    }
    for i, (sidecar, needle) in enumerate(cases.items()):
        folder = tmp_path / str(i)
        folder.mkdir()
        (folder / "leg.urdf").write_text(tree)
        (folder / "leg.yaml").write_text(sidecar)
        with pytest.raises(MalformedDescription, match=needle):
            mechkit.load(folder / "leg.urdf")


def test_mjcf_errors(tmp_path):
    rssr = (FIXTURES / "rssr.xml").read_text()
    cases = {
        rssr.replace('body2="rocker_link"', 'body2="rocker_lnk"'): "MuJoCo could not compile",
        "<robot/>": "starts with <mujoco>",
    }
    for i, (text, needle) in enumerate(cases.items()):
        with pytest.raises(MalformedDescription, match=needle):
            mechkit.load(_urdf(tmp_path, text, f"m{i}.xml"))


def test_xacro_errors(tmp_path):
    with pytest.raises(InvalidParameters, match="no such xacro:arg"):
        mechkit.load(FIXTURES / "watt_six_bar.urdf.xacro", thet=1.0)
    with pytest.raises(InvalidParameters, match="not a xacro file"):
        mechkit.load(FIXTURES / "slider_crank.urdf", crank=0.2)
    with pytest.raises(MalformedDescription):
        mechkit.load(FIXTURES / "watt_six_bar.urdf.xacro", theta=3.0, b=0.01)  # the circles do not meet


@pytest.mark.parametrize("args, needle", [
    (["report", "tests/fixtures/nowhere.urdf"], "no such file"),
    (["report", "tests/fixtures"], "directory"),
    (["snapshot", "UNACTUATED", "--q", "0.3"], "unactuated"),
    (["urdf", "tests/fixtures/slider_crank.urdf", "--set", "crank=1"], "not a xacro file"),
])
def test_cli_errors_are_one_line(args, needle, tmp_path):
    if "UNACTUATED" in args:
        text = SLIDER[:SLIDER.index("<transmission")] + SLIDER[SLIDER.index("</transmission>") + 15:]
        args = [a if a != "UNACTUATED" else str(_urdf(tmp_path, text)) for a in args] + ["-o", str(tmp_path / "s.html")]
    out = subprocess.run([sys.executable, "-m", "mechkit", *args], capture_output=True, text=True, check=False,
                         cwd=Path(__file__).parent.parent)
    assert out.returncode == 2, out.stderr
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and needle in lines[0] and "Traceback" not in out.stderr
    assert not (tmp_path / "s.html").exists()
