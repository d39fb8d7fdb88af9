"""`mechkit.export.urdf`: every mechanism written as mechkit's URDF and read back is the same mechanism (DOF,
actuators, springs, couplings, home, the fall released at home to 1e-10, and where the motors hold it the
gravity efforts to 1e-12 and reactions to 1e-10), whatever it was
read from or however reduced; what URDF cannot say is refused by name."""

from __future__ import annotations

import numpy as np
import pytest
from tests_support import FIXTURES

import mechkit
from mechkit.base.exceptions import MethodUnavailable
from mechkit.export import to_urdf

#: source x reduction written and read back (see docs/your_own_mechanism.md, "Writing a mechanism").
ROUND_TRIPS = [
    ("four_bar", {}),
    ("ten_bar", {}),
    ("five_bar", {"lock": {"prox1": 1.5}}),
    ("ten_bar", {"lock": {"R1": 0.3}}),
    (FIXTURES / "slider_crank.urdf", {}),
    (FIXTURES / "watt_six_bar.urdf.xacro", {}),
    (FIXTURES / "field" / "urdf_plus" / "four_bar.urdf", {}),
    (FIXTURES / "rssr.xml", {}),
    (FIXTURES / "field" / "sdf" / "four_bar_gearbox.sdf", {}),
]
#: what URDF cannot say: source, options, the refusal's words.
REFUSED = [
    (FIXTURES / "field" / "urdf_plus" / "mit_humanoid.urdf", {}, "coupling 'right_ankle_transmission' is not one"),
    (FIXTURES / "leg.urdf", {}, "joint 'rod2_top_z' is a JointModelSpherical: URDF has no such joint"),
    (FIXTURES / "field" / "menagerie" / "robotiq_2f85" / "2f85.xml", {}, "a URDF transmission drives one joint"),
    (FIXTURES / "field" / "menagerie" / "agility_cassie" / "cassie.xml", {"fix": ["cassie-pelvis"]}, "URDF has no"),
]


def _name(source, options) -> str:
    return f"{getattr(source, 'name', source)}{'-' + '-'.join(options) if options else ''}"


@pytest.mark.parametrize("source, options", ROUND_TRIPS, ids=[_name(*c) for c in ROUND_TRIPS])
def test_written_and_read_back_it_is_the_same_mechanism(tmp_path, source, options):
    m = mechkit.load(source, **options)
    path = tmp_path / "written.urdf"
    path.write_text(to_urdf(m))
    w = mechkit.load(path)
    assert w.home_mobility.dof == m.home_mobility.dof and tuple(w.actuated) == tuple(m.actuated)
    assert len(w.springs.springs) == len(m.springs.springs)
    assert len(w.closure_model.couplings) == len(m.closure_model.couplings)
    assert w.joint_values(w.home_q).keys() == m.joint_values(m.home_q).keys()
    for joint, value in m.joint_values(m.home_q).items():
        assert np.allclose(w.joint_values(w.home_q)[joint], value, atol=1e-10), joint
    zero_m, zero_w = np.zeros(m.model.nv), np.zeros(w.model.nv)
    fall_m = m.forward_dynamics(m.home_q, zero_m, zero_m, method="kkt").a  # released at home, unpowered
    fall_w = w.forward_dynamics(w.home_q, zero_w, zero_w, method="kkt").a
    one = [j for j in m.model.names[1:] if m.model.joints[m.model.getJointId(j)].nv == 1]
    a_scale = max([1.0, *np.abs(fall_m)])
    for joint in one:
        assert abs(fall_w[w.v_index(joint)] - fall_m[m.v_index(joint)]) <= 1e-10 * a_scale, joint
    if m.home_mobility.dof != len(m.actuated):  # the motors cannot hold it still: the fall is the check
        return
    a, b = m.inverse_dynamics(m.home_q, zero_m, zero_m), w.inverse_dynamics(w.home_q, zero_w, zero_w)
    scale = max([1.0, *(abs(u) for u in a.efforts.values())])
    for actuator, effort in a.efforts.items():
        assert abs(b.efforts[actuator] - effort) <= 1e-12 * scale, actuator
    shared = set(a.reactions) & set(b.reactions)
    assert len(shared) >= m.model.njoints - 1
    wrench_scale = max([1.0, *(np.abs(r.wrench).max() for r in a.reactions.values())])
    for joint in shared:
        assert np.max(np.abs(a.reactions[joint].wrench - b.reactions[joint].wrench)) <= 1e-10 * wrench_scale, joint


def test_a_registered_mechanism_keeps_its_template_text_and_declares_its_actuators():
    m = mechkit.load("four_bar")
    text = to_urdf(m)
    assert text.startswith(m.urdf[: m.urdf.rindex("</robot>")])
    assert '<joint name="crank">' in text and '<mechkit:home joint="crank" value="0.6"' in text


def test_a_reduced_mechanism_keeps_its_beams_limits_and_visuals(tmp_path):
    m = mechkit.load("five_bar", lock={"prox1": 1.5})
    text = to_urdf(m)
    assert text.count("<mechkit:beam ") == 4 and "<visual>" in text
    assert 'lower="-25.0"' in text and 'upper="25.0"' in text  # the file's limits, not wide ones


@pytest.mark.parametrize("source, options, words", REFUSED, ids=[_name(s, o) for s, o, _ in REFUSED])
def test_what_urdf_cannot_say_is_refused_by_name(source, options, words):
    with pytest.raises(MethodUnavailable, match=words):
        to_urdf(mechkit.load(source, **options))


@pytest.mark.parametrize(
    "fmt, suffix", [("urdf", ".urdf"), ("extended-urdf", ".urdf"), ("urdf-plus", ".urdf"), ("mjcf", ".xml")]
)
def test_every_format_keeps_an_sdformat_gearbox_and_spring(tmp_path, fmt, suffix):
    """The SDFormat four-bar's gearbox (a coupling) and rocker spring: the Extended-URDF and MJCF writers used
    to drop both in silence (the file read back with DOF 2 for 1 and another holding effort)."""
    from mechkit.export import export_command

    m = mechkit.load(FIXTURES / "field" / "sdf" / "four_bar_gearbox.sdf")
    (path, *_) = export_command(m, fmt, tmp_path / f"written{suffix}")
    w = mechkit.load(path)
    assert w.home_mobility.dof == 1 and len(w.closure_model.couplings) == 1
    zero_m, zero_w = np.zeros(m.model.nv), np.zeros(w.model.nv)
    held = m.inverse_dynamics(m.home_q, zero_m, zero_m).efforts["motor"]
    assert w.inverse_dynamics(w.home_q, zero_w, zero_w).efforts["motor"] == pytest.approx(held, rel=1e-9)
