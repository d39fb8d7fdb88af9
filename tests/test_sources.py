"""`mechkit.sources`: mechanisms from files (URDF with loops, Extended URDF, xacro, MJCF): the four-way
agreement with the registered mechanisms; the team's fixtures with their structure and self-checks."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from tests_support import FIXTURES

import mechkit
from mechkit.export import to_extended_urdf, to_mjcf
from mechkit.report import report


def _with_transmissions(mech: mechkit.Mechanism) -> str:
    """The registered mechanism's URDF, its actuators written as <transmission> and its home as <mechkit:home>."""
    extra = "".join(
        f'<transmission name="{j}_motor"><joint name="{j}"/></transmission>'
        f'<mechkit:home joint="{j}" value="{float(mech.home_q[mech.q_index(j)])!r}"/>'
        for j in mech.actuated
    )
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
    return ref, {
        "urdf": mechkit.load(tmp_path / "loops.urdf", guess=guess),
        "extended-urdf": mechkit.load(tmp_path / "ext" / "tree.urdf", home=home, guess=guess),
        "mjcf": mechkit.load(tmp_path / "model.xml"),
    }


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
            assert (
                max(
                    abs(got.efforts[j] - expected.efforts[j]) / max(1.0, abs(expected.efforts[j])) for j in ref.actuated
                )
                < 1e-12
            ), how
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
