"""Mechanisms from files: URDF with loops, Extended URDF, xacro, MJCF; the four-way agreement with the
registered mechanisms; the team's fixtures; the CLI on paths."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import mechkit
from mechkit.cli import main
from mechkit.export import to_extended_urdf, to_mjcf
from mechkit.report import report

FIXTURES = Path(__file__).parent / "fixtures"
CONTRACT_KEYS = {"name", "nq", "nv", "actuated", "closures", "dof", "dof_gruebler", "redundant_constraints", "checks"}


def _with_transmissions(mech: mechkit.Mechanism) -> str:
    """The registered mechanism's URDF, its actuators written as <transmission> and its home as <mechkit:home>."""
    extra = "".join(f'<transmission name="{j}_motor"><joint name="{j}"/></transmission>'
                    f'<mechkit:home joint="{j}" value="{float(mech.home_q[mech.q_index(j)])!r}"/>' for j in mech.actuated)
    return mech.urdf.replace("</robot>", extra + "</robot>")


def _four_ways(name: str, tmp_path: Path) -> tuple[mechkit.Mechanism, dict[str, mechkit.Mechanism]]:
    ref = mechkit.load(name)
    guess = ref.joint_values(ref.home_q)
    (tmp_path / "loops.urdf").write_text(_with_transmissions(ref))
    (tmp_path / "ext").mkdir()
    urdf, sidecar = to_extended_urdf(ref)
    (tmp_path / "ext" / "tree.urdf").write_text(urdf)
    (tmp_path / "ext" / "tree.yaml").write_text(sidecar)
    (tmp_path / "model.xml").write_text(to_mjcf(ref))
    home = {j: ref.home_q[ref.q_index(j)] for j in ref.actuated}
    return ref, {"urdf": mechkit.load(tmp_path / "loops.urdf", guess=guess),
                 "extended-urdf": mechkit.load(tmp_path / "ext" / "tree.urdf", home=home, guess=guess),
                 "mjcf": mechkit.load(tmp_path / "model.xml")}


def _close(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.abs(np.asarray(a) - np.asarray(b))) / max(1.0, np.max(np.abs(b))))


@pytest.mark.parametrize("name", ["four_bar", "parallel_2t1r"])
def test_four_ways_give_the_same_mobility_efforts_and_reactions(name, tmp_path):
    """Registered name, URDF with loops, Extended URDF and mechkit's MJCF read back: one mechanism."""
    ref, loaded = _four_ways(name, tmp_path)
    n = len(ref.actuated)
    q1 = ref.home_q
    q2 = ref.assemble(np.array([ref.home_q[ref.q_index(j)] for j in ref.actuated]) + 0.05, guess=q1)
    for m in loaded.values():
        assert list(m.actuated) == list(ref.actuated)
        assert _close(m.home_q, ref.home_q) < 1e-12
        mob, mob_ref = m.mobility(), ref.mobility()
        assert (mob.dof, mob.redundant, mob.rank) == (mob_ref.dof, mob_ref.redundant, mob_ref.rank)
        assert m.structure.kutzbach == ref.structure.kutzbach == ref.spec.gruebler_dof
    for q in (q1, q2):
        v = ref.velocities(q, np.linspace(0.5, 1.0, n))
        a = ref.accelerations(q, v, np.linspace(-0.3, 0.4, n))
        expected = ref.inverse_dynamics(q, v, a)
        cuts = {c.name for c in ref.closures}
        for how, m in loaded.items():
            got = m.inverse_dynamics(q, v, a)
            assert max(abs(got.efforts[j] - expected.efforts[j]) / max(1.0, abs(expected.efforts[j])) for j in ref.actuated) < 1e-12, how
            assert len(got.reactions) == len(expected.reactions)
            for (j1, r1), (j2, r2) in zip(got.reactions.items(), expected.reactions.items()):
                assert j1 == j2 or how == "extended-urdf"  # the sidecar names no cut: named after its frames
                assert _close(r1.wrench, r2.wrench) < 1e-12, (how, j1)
                # a file's single point anchor is a ball joint: it carries no moment, where the registered
                # hinge's moments normal to its axis are indeterminate in a planar loop; forces alike
                flags = slice(0, 3) if j2 in cuts else slice(0, 6)
                assert (r1.determinate[flags] == r2.determinate[flags]).all() and r1.support == r2.support, (how, j1)


FIXTURE_FACTS = {  # file -> (format, actuated, numerical DOF, Kutzbach, idle bodies, loop kinds)
    "slider_crank.urdf": ("urdf", ["crank"], 1, 1, {}, ["planar"]),
    "watt_six_bar.urdf.xacro": ("xacro", ["crank"], 1, 1, {}, ["planar", "planar"]),
    "rssr.xml": ("mjcf", ["crank"], 2, 2, {"coupler_link": 1}, ["spatial"]),
    "leg.urdf": ("extended-urdf", ["hip", "knee_motor"], 4, 4, {"rod1": 1, "rod2": 1}, ["spatial", "spatial"]),
}


@pytest.mark.parametrize("file", list(FIXTURE_FACTS))
def test_fixtures_load_with_their_structure_and_pass_the_self_checks(file):
    fmt, actuated, dof, kutzbach, idle, kinds = FIXTURE_FACTS[file]
    m = mechkit.load(FIXTURES / file)
    r = report(m)
    assert r["summary"].startswith(f"read from the {fmt} file")
    assert r["actuated"] == actuated and r["dof"] == dof and r["dof_gruebler"] == kutzbach
    assert r["redundant_constraints"] == 0 and r["idle"] == idle
    assert [lp["kind"] for lp in r["loops"]] == kinds
    assert dof - sum(idle.values()) == len(actuated)  # the mobility that matters is driven
    assert all(value < 1e-9 for value in r["checks"].values()), r["checks"]


def test_xacro_keyword_parameters_are_xacro_arguments():
    """The Watt II written at another crank angle: its home assembly moves, the loops stay closed."""
    a = mechkit.load(FIXTURES / "watt_six_bar.urdf.xacro")
    b = mechkit.load(FIXTURES / "watt_six_bar.urdf.xacro", theta=1.1, a=0.12)
    assert b.urdf != a.urdf
    shown = {row["name"]: row["value"] for row in report(b)["parameters"]}
    assert shown["theta"] == "1.1" and shown["a"] == "0.12" and shown["b"] == "0.35"  # given, given, default
    assert np.max(np.abs(b.closure_residual(b.home_q))) < 1e-12
    pin_c = b.model.getFrameId("coupler_C")
    assert b.data.oMf[pin_c].translation[0] != pytest.approx(a.data.oMf[a.model.getFrameId("coupler_C")].translation[0])


def test_a_continuous_joint_is_an_angle_at_the_boundary(tmp_path):
    """Pinocchio gives a continuous joint (cos, sin); inputs, home and reports use the angle."""
    text = (FIXTURES / "slider_crank.urdf").read_text().replace('name="crank" type="revolute"', 'name="crank" type="continuous"')
    (tmp_path / "sc.urdf").write_text(text)
    m = mechkit.load(tmp_path / "sc.urdf")
    assert m.model.nq == m.model.nv + 1
    assert m.joint_values(m.home_q)["crank"] == pytest.approx(0.5, abs=1e-15)
    i = m.q_index("crank")
    assert m.home_q[i:i + 2] == pytest.approx([np.cos(0.5), np.sin(0.5)], abs=1e-15)
    q = m.assemble({"crank": 2.0}, guess=m.home_q)
    assert m.joint_values(q)["crank"] == pytest.approx(2.0, abs=1e-14)
    assert report(m)["home"]["crank"] == pytest.approx(0.5, abs=1e-15)
    ref = mechkit.load(FIXTURES / "slider_crank.urdf")  # the same linkage with a revolute crank
    assert m.joint_values(q)["slider"] == pytest.approx(ref.joint_values(ref.assemble({"crank": 2.0}, guess=ref.home_q))["slider"], abs=1e-12)


def test_actuators_come_from_the_file_or_the_override_and_an_unactuated_model_says_so(tmp_path):
    text = (FIXTURES / "slider_crank.urdf").read_text()
    start, end = text.index("<transmission"), text.index("</transmission>") + len("</transmission>")
    (tmp_path / "bare.urdf").write_text(text[:start] + text[end:])
    bare = mechkit.load(tmp_path / "bare.urdf")
    assert bare.actuated == () and report(bare)["actuated"] == []
    with pytest.raises(mechkit.InvalidParameters, match="unactuated"):
        bare.velocities(bare.home_q, [1.0])
    driven = mechkit.load(tmp_path / "bare.urdf", actuated=["slider"])
    assert driven.actuated == ("slider",)
    assert mechkit.load("four_bar", actuated=["rocker"]).actuated == ("rocker",)


def test_cli_takes_a_path_set_and_actuated(tmp_path, capsys):
    assert main(["report", str(FIXTURES / "watt_six_bar.urdf.xacro"), "--set", "theta=0.8", "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert CONTRACT_KEYS | {"idle", "loops", "rows_avoided"} <= set(r)
    assert r["dof"] == 1 and r["rows_avoided"] == 6
    assert main(["report", str(FIXTURES / "slider_crank.urdf"), "--actuated", "slider", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["actuated"] == ["slider"]
    assert main(["report", str(FIXTURES / "slider_crank.urdf"), "--set", "rows=spatial", "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert r["loops"][0]["chosen"] == "forced" and r["redundant_constraints"] == 3 and r["dof"] == 1
    out = tmp_path / "watt.xml"
    assert main(["export", str(FIXTURES / "watt_six_bar.urdf.xacro"), "--format", "mjcf", "-o", str(out)]) == 0
    again = mechkit.load(out)
    assert again.mobility().dof == 1 and again.actuated == ("crank",) and again.structure.kutzbach == 1
