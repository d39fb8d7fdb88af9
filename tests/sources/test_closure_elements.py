"""`mechkit.sources.closure_elements`: another tool's loop closures found in every file of a description,
with their line, nested parts not counted twice, what cannot change the kinematics left alone."""

from __future__ import annotations

from pathlib import Path

from tests_support import FIXTURES, ROOT

from mechkit.sources.closure_elements import ClosureElement, refusal, unread_closures
from mechkit.sources.input_files import description_files

CLOSURES = FIXTURES / "closures"


def test_each_tool_s_closure_is_found_once_at_its_line(tmp_path):
    """A Drake distance constraint (URDF) and a Drake joint in SDFormat, each once, its parts not counted."""
    path = tmp_path / "model.sdf"
    path.write_text(
        '<sdf version="1.9" xmlns:drake="http://drake.mit.edu"><model name="m"><link name="a"/><link name="b"/>\n'
        '<drake:joint name="j" type="screw"><parent>a</parent>\n<child>b</child></drake:joint>\n'
        "<drake:distance_constraint><drake:distance_constraint_body_A>a</drake:distance_constraint_body_A>"
        "</drake:distance_constraint></model></sdf>"
    )
    found = unread_closures([path])
    assert [(f.element, f.line) for f in found] == [("drake:joint", 2), ("drake:distance_constraint", 4)]


def test_what_mechkit_now_reads_is_not_listed():
    """Drake's ball constraint (URDF, SDFormat, inside an included macro), its bushing (URDF, SDFormat) and
    Gazebo's joint are read
    (`mechkit.sources.drake_elements`)."""
    files = [CLOSURES / f"four_bar_{k}.urdf" for k in ("drake_ball", "drake_bushing", "gazebo_joint")]
    files += [CLOSURES / "four_bar_drake_ball.sdf", CLOSURES / "four_bar_drake_bushing.sdf"]
    assert unread_closures([*files, *description_files(CLOSURES / "leg_pair.urdf.xacro")]) == []


def test_what_mechkit_reads_or_what_cannot_close_a_loop_is_not_listed(tmp_path):
    """The catalogue's own files (mechkit loops, beams, springs), an MJCF file with equalities, and Drake
    or Gazebo elements that change no kinematics (collision properties, a plugin, materials)."""
    files = [*sorted((ROOT / "urdf").glob("*.urdf")), FIXTURES / "rssr.xml"]
    other = tmp_path / "other.urdf"
    other.write_text(
        '<robot name="r" xmlns:drake="http://drake.mit.edu"><link name="a"><collision><geometry><box size="1 1 1"/>'
        "</geometry><drake:proximity_properties><drake:mu_static value='1'/></drake:proximity_properties></collision>"
        '</link><gazebo reference="a"><material>Gazebo/Grey</material></gazebo><gazebo><plugin name="p" '
        'filename="libp.so"/></gazebo></robot>'
    )
    assert unread_closures([*files, other]) == []


def test_unparsable_files_and_sidecars_are_left_to_their_readers(tmp_path):
    (tmp_path / "bad.urdf").write_text("<robot><drake:ball_constraint>")  # unbound prefix: not XML
    (tmp_path / "x.yaml").write_text("closed_loop: []\n")
    assert unread_closures([tmp_path / "bad.urdf", tmp_path / "x.yaml"]) == []


def test_the_refusal_names_the_first_the_count_and_what_to_do():
    found = [ClosureElement("drake:ball_constraint", Path("/a/leg.urdf"), 12, "a Drake constraint")] * 3
    message = str(refusal(found))
    assert message.startswith("leg.urdf:12: <drake:ball_constraint> (a Drake constraint): ")
    assert "and 2 more such element(s)" in message and "<mechkit:loop>" in message
    assert "--ignore-unknown-closures" in message
