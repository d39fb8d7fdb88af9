"""`mechkit export --format urdf+` then `mechkit.load` of the file: the same mechanism, for every registered
mechanism URDF+ can write and for field files with its loop kinds (fixed loops from Gepetto's 6d pairs),
couplings (URDF+'s authors' gear transmissions), rotors and mimic joints (example-robot-data's Panda).

Same: the same joints, actuators, cut kinds and couplings; the same home assembly, closed on the file's
model; the same DOF; the same constrained forward dynamics there (at rest under gravity, and under a
unit effort of the first actuator); the same holding efforts. URDF+ carries the home inputs
(`<mechkit:home>`), not the assembly branch: the re-reading is given the home as its guess. What URDF+
cannot write (a ball cut, a tree of ball joints, a tendon actuator) is refused by name.
"""

from __future__ import annotations

import contextlib
import io
from pathlib import Path

import numpy as np
import pytest
from tests_support import PANDA

import mechkit
from mechkit.catalog import registry
from mechkit.cli import main
from mechkit.report import holding
from mechkit.sources import read

FIELD = Path(__file__).resolve().parents[1] / "fixtures" / "field"
#: What URDF+ cannot write, and what the refusal says.
REFUSED = {
    "rocket_gimbal": "cut 'a_ball_joint' is spherical",
    str(FIELD / "menagerie" / "agility_cassie" / "cassie.xml"): "is a JointModelSpherical: URDF has no such joint",
    str(FIELD / "gepetto" / "cassie_like" / "robot.urdf"): "is a JointModelSpherical: URDF has no such joint",
    str(FIELD / "menagerie" / "robotiq_2f85" / "2f85.xml"): "actuator 'fingers_actuator' drives a tendon",
}
SOURCES = (
    [n for n in registry.names() if n not in REFUSED]
    + [str(FIELD / "urdf_plus" / f) for f in ("four_bar.urdf", "mit_humanoid.urdf", "revolute_rotor_chain.urdf")]
    + [str(FIELD / "gepetto" / r / "robot.urdf") for r in ("5bar_linkage", "robot_delta")]
    + [str(PANDA)]
)


def _export(source: str, path: Path) -> tuple[int, str]:
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        code = main(["export", source, "--format", "urdf+", "-o", str(path)])
    return code, err.getvalue()


def _by_name(m, values: np.ndarray) -> dict[str, np.ndarray]:
    return {
        m.model.names[j]: values[m.model.idx_vs[j] : m.model.idx_vs[j] + m.model.nvs[j]]
        for j in range(1, m.model.njoints)
    }


def _in_order(m, named: dict[str, np.ndarray]) -> np.ndarray:
    out = np.zeros(m.model.nv)
    for name, value in named.items():
        out[m.v_index(name) : m.v_index(name) + len(value)] = value
    return out


@pytest.mark.parametrize(
    "source", SOURCES, ids=[Path(s).parent.name + "/" + Path(s).name if "/" in s else s for s in SOURCES]
)
def test_export_then_load_gives_the_same_mechanism(source, tmp_path):
    m = mechkit.load(source)
    path = tmp_path / "exported.urdf"
    assert _export(source, path) == (0, "")
    desc = read(path)
    assert desc.format == "urdf+" or not m.closures
    r = mechkit.load(path, guess={k: v for k, v in m.joint_values(m.home_q).items() if np.ndim(v) == 0})
    assert list(r.model.names) == list(m.model.names) and r.actuated == m.actuated
    assert [(c.name, c.kind) for c in r.closures] == [(c.name, c.kind) for c in m.closures]
    assert r.closure_model.couplings == m.closure_model.couplings
    np.testing.assert_allclose(r.home_q, m.home_q, atol=1e-9)
    assert np.max(np.abs(r.closure_residual(m.home_q)), initial=0.0) < 1e-12
    assert r.mobility().dof == m.mobility().dof
    efforts = [np.zeros(m.model.nv)]
    if m.actuated:
        efforts.append(m.generalized_forces({m.actuated[0]: 1.0}))
    for effort in efforts:
        ours = m.forward_dynamics(m.home_q, np.zeros(m.model.nv), effort, "kkt").a
        theirs = r.forward_dynamics(m.home_q, np.zeros(r.model.nv), _in_order(r, _by_name(m, effort)), "kkt").a
        np.testing.assert_allclose(
            _in_order(m, _by_name(r, theirs)), ours, atol=1e-8 * max(1.0, float(np.max(np.abs(ours))))
        )
    held, again = holding(m), holding(r)
    assert held.keys() == again.keys()
    if "efforts" in held:
        for actuator, effort in held["efforts"].items():
            assert again["efforts"][actuator] == pytest.approx(effort, abs=1e-8 * max(1.0, abs(effort)))


@pytest.mark.parametrize("source", list(REFUSED), ids=[Path(s).name for s in REFUSED])
def test_what_urdf_plus_cannot_write_is_refused_by_name(source, tmp_path):
    code, err = _export(source, tmp_path / "exported.urdf")
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1 and "urdf+ export unavailable" in lines[0] and REFUSED[source] in lines[0]
    assert not (tmp_path / "exported.urdf").exists()
