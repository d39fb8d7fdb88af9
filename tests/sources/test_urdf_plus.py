"""URDF+ (mechkit.sources.urdf_plus) on its authors' own example models (generalized_rbda): loops and
couplings read into cuts and coupling rows, checked against an independent reading of the same files
(an XML parser and Pinocchio), then DOF and holding torques by `independent.study` on both."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from mechkit.cli import main
from mechkit.sources import read
from mechkit.sources.urdf_plus import read_urdf_plus

from .independent import cuts_of, require_closed, study, urdf_plus_load

FIELD = Path(__file__).parent.parent / "fixtures" / "field" / "urdf_plus"


@pytest.mark.parametrize("file, dof", [("four_bar.urdf", 1), ("six_bar.urdf", 3)])
def test_a_loop_is_a_revolute_cut_at_its_frames_and_the_linkage_agrees(file, dof):
    """The four-bar and the six-bar: one revolute loop each, its frames where the file puts them; from
    the same start both readings close to the same configuration, with the same DOF and the same
    torques of the independent coordinates holding gravity (about the planes' normal: gravity is
    turned into the plane for the test)."""
    desc = read_urdf_plus(FIELD / file)
    theirs, their_cuts, couplings, motors = urdf_plus_load(FIELD / file)
    assert couplings == [] and desc.couplings == () and desc.format == "urdf+"
    assert [(c.name, c.kind) for c in desc.closures] == [(c.name, "revolute") for c in their_cuts]
    ours = pin.buildModelFromXML(desc.urdf)
    cuts = cuts_of(ours, desc.closures)
    for a, b in zip(cuts, their_cuts):
        assert (ours.names[a.joint_a], ours.names[a.joint_b]) == (theirs.names[b.joint_a], theirs.names[b.joint_b])
        assert a.place_a.isApprox(b.place_a, 1e-14) and a.place_b.isApprox(b.place_b, 1e-14)
        np.testing.assert_allclose(a.axis, b.axis / np.linalg.norm(b.axis), atol=1e-15)
    q0 = pin.neutral(ours)
    q0 = pin.integrate(
        ours, q0, np.linspace(0.4, -0.3, ours.nv)
    )  # off the flat, singular pose the files are written at
    for model in (ours, theirs):
        model.gravity.linear = np.array([0.0, -9.81, 0.0])
    found, ref = study(ours, cuts, motors, q0), study(theirs, their_cuts, motors, q0)
    require_closed(file, ours, cuts, found.q)
    np.testing.assert_allclose(found.q, ref.q, atol=1e-12)
    assert found.dof == ref.dof == dof and found.holds and ref.holds and found.torques_unique
    for motor in motors:
        assert abs(found.torques[motor]) > 1e-3
        assert found.torques[motor] == pytest.approx(ref.torques[motor], abs=1e-8 * max(1.0, abs(ref.torques[motor])))


def test_couplings_are_rows_over_the_joints_below_the_nearest_common_ancestor():
    """The MIT humanoid: 18 gear transmissions, rotor = ratio x link; the ankle rotor sits on the thigh,
    so its row is rotor = 12 (knee + ankle). The rows cut the floating tree's 42 freedoms to 24."""
    desc = read(FIELD / "mit_humanoid.urdf")
    model, cuts, couplings, _ = urdf_plus_load(FIELD / "mit_humanoid.urdf")
    assert desc.closures == () and cuts == []
    assert list(desc.couplings) == couplings and len(couplings) == 18
    ankle = next(c for c in desc.couplings if c.name == "right_ankle_transmission")
    assert ankle.follower == (("right_hipy_to_ankle_rotor", 1.0),) and ankle.polynomial == (0.0, 12.0)
    assert set(ankle.leader) == {("right_knee_to_ankle", 1.0), ("right_hipy_to_knee_link", 1.0)}
    assert pin.buildModelFromXML(desc.urdf).nv == model.nv == 42
    q0 = pin.integrate(model, pin.neutral(model), np.linspace(-0.2, 0.3, model.nv))
    found = study(model, [], [], q0, couplings=desc.couplings)
    assert found.closed and found.dof == 24


@pytest.mark.parametrize(
    "file, needle",
    [
        ("planar_leg_linkage.urdf", "link 'thigh': inertia"),
        ("mini_cheetah_leg.urdf", "link 'abduct': inertia"),
    ],
)
def test_the_authors_files_no_body_can_have_are_one_named_line_from_the_cli(file, needle, capsys):
    assert main(["report", str(FIELD / file)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and needle in err[0], err


FOUR_BAR = (FIELD / "four_bar.urdf").read_text()
HUMANOID = (FIELD / "mit_humanoid.urdf").read_text()
LOOP = FOUR_BAR[FOUR_BAR.index("<loop") : FOUR_BAR.index("</loop>") + len("</loop>")]


def _edit(text: str, old: str, new: str) -> str:
    assert old in text, old
    return text.replace(old, new)


#: URDF+ files with one slip each, the style of the field's (ACDC4Robot's exporter writes <sucessor name=...>).
MALFORMED = {
    "a loop to a link the URDF lacks": (
        _edit(FOUR_BAR, '<successor link="link3">', '<successor link="link4">'),
        "<loop name='loop1'> <successor>: link='link4' is not a link of the URDF",
    ),
    "a coupling to a link the URDF lacks": (
        _edit(HUMANOID, '<predecessor link="right_hip_rz_link"/>', '<predecessor link="right_hipz"/>'),
        "<coupling name='right_hipz_transmission'> <predecessor>: link='right_hipz' is not a link",
    ),
    "the exporter's spelling of successor": (
        _edit(
            FOUR_BAR,
            '<successor link="link3">\n            <origin xyz="0.5 0.0 0.0"/>\n        </successor>',
            '<sucessor name="link3">\n            <origin xyz="0.5 0.0 0.0"/>\n        </sucessor>',
        ),
        "missing <successor link=...> (found <sucessor>",
    ),
    "an unknown loop type": (
        _edit(FOUR_BAR, 'type="revolute">\n        <predecessor', 'type="ball">\n        <predecessor'),
        "type 'ball' is not one of ('revolute', 'continuous', 'prismatic', 'fixed', 'planar')",
    ),
    "a planar loop": (
        _edit(FOUR_BAR, 'type="revolute">\n        <predecessor', 'type="planar">\n        <predecessor'),
        "URDF+ reader unavailable: <loop name='loop1'> is a planar loop",
    ),
    "two constraints of one name": (
        _edit(HUMANOID, '<coupling name="left_hipz_transmission">', '<coupling name="right_hipz_transmission">'),
        "<coupling name='right_hipz_transmission'>: declared twice",
    ),
    "a ratio that is not a number": (
        _edit(HUMANOID, '<ratio value="12.0"/>', '<ratio value="twelve"/>'),
        "value 'twelve' is not a number",
    ),
    "a zero axis": (
        _edit(FOUR_BAR, '</successor>\n        <axis xyz="0 0 1"/>', '</successor>\n        <axis xyz="0 0 0"/>'),
        "<loop name='loop1'> <axis>: xyz is a zero vector",
    ),
    "an origin of two numbers": (
        _edit(
            FOUR_BAR,
            '<origin xyz="0.5 0.0 0.0"/>\n        </successor>',
            '<origin xyz="0.5 0.0"/>\n        </successor>',
        ),
        "xyz='0.5 0.0' is not three numbers",
    ),
    "a loop from a link to itself": (
        _edit(FOUR_BAR, '<successor link="link3">', '<successor link="link2">'),
        "predecessor and successor are the same link 'link2'",
    ),
    "a coupling of a link and its own parent": (
        _edit(
            HUMANOID,
            '<predecessor link="right_hip_rz_link"/>\n    <successor link="right_hip_rz_rotor"/>',
            '<predecessor link="right_hip_rz_link"/>\n    <successor link="Floating Base"/>',
        ),
        "a link has no moving joint below the links' nearest common ancestor",
    ),
}


@pytest.mark.parametrize("case", list(MALFORMED))
def test_a_malformed_urdf_plus_file_is_one_named_line_from_the_cli(case, tmp_path, capsys):
    text, needle = MALFORMED[case]
    (tmp_path / "robot.urdf").write_text(text)
    assert main(["report", str(tmp_path / "robot.urdf")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and needle in err[0], err


def test_urdf_plus_constraints_and_a_sidecar_are_two_conventions_refused(tmp_path, capsys):
    (tmp_path / "robot.urdf").write_text(FOUR_BAR)
    (tmp_path / "robot.yaml").write_text("closed_loop: []\ntype: []\n")
    assert main(["report", str(tmp_path / "robot.urdf")]) == 2
    assert "one loop convention per file" in capsys.readouterr().err
