"""`mechkit.catalog.contract`: every registered spec fulfils the contract, a spec refuses hooks it cannot
use, and the committed URDF of every spec is its template at the defaults, which every consumer accepts."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys

import pytest

from mechkit import load
from mechkit.base.resources import urdf_dir, xacro_dir
from mechkit.catalog.contract import BENCH_QUANTITIES, MechanismSpec
from mechkit.catalog.registry import ENTRIES, get_spec, specs
from mechkit.export import to_urdf
from mechkit.sources.urdf import build_model

NAMES = list(specs())


@pytest.mark.parametrize("name", NAMES)
def test_committed_urdf_matches_the_xacro_template(name):
    path = urdf_dir() / f"{name}.urdf"
    assert path.exists(), f"urdf/{name}.urdf missing: run python tools/generate_urdfs.py {name}"
    text, template = path.read_text(), specs()[name].default_urdf()
    stale = f"urdf/{name}.urdf is stale: run tools/generate_urdfs.py"
    # the template's text byte for byte, then the spec's actuators, home and branch (`mechkit.export.urdf`)
    assert text.startswith(template[: template.rindex("</robot>")]) and text == to_urdf(load(name)), stale


@pytest.mark.parametrize("name", NAMES)
def test_urdfdom_accepts(name, tmp_path):
    # the venv's bin (where pip puts urdfdom's check_urdf) may not be on PATH
    exe = shutil.which(
        "check_urdf", path=os.pathsep.join([os.path.dirname(sys.executable), os.environ.get("PATH", "")])
    )
    if exe is None:
        pytest.skip("check_urdf (urdfdom) not on PATH")
    out = subprocess.run([exe, str(urdf_dir() / f"{name}.urdf")], check=False, capture_output=True, text=True)
    assert out.returncode == 0 and "Successfully Parsed" in out.stdout, out.stdout + out.stderr


@pytest.mark.parametrize("name", NAMES)
def test_yourdfpy_accepts(name):
    yourdfpy = pytest.importorskip("yourdfpy")
    robot = yourdfpy.URDF.load(str(urdf_dir() / f"{name}.urdf"), load_meshes=False, build_scene_graph=False)
    assert robot.validate()


@pytest.mark.parametrize("name", NAMES)
def test_mujoco_compiles(name):
    mujoco = pytest.importorskip("mujoco")
    model = mujoco.MjModel.from_xml_string((urdf_dir() / f"{name}.urdf").read_text())
    assert model.njnt == build_model((urdf_dir() / f"{name}.urdf").read_text()).njoints - 1


@pytest.mark.parametrize("entry", ENTRIES, ids=lambda e: e.name)
def test_contract(entry):
    spec = get_spec(entry.name)
    assert isinstance(spec, MechanismSpec) and spec.name == entry.name
    assert spec.summary == entry.summary
    assert spec.template_path.is_file() and spec.template_path.parent == xacro_dir()
    assert (urdf_dir() / f"{entry.name}.urdf").is_file()
    params = spec.params()
    assert spec.actuated_joints(params) and spec.gruebler_dof >= 1
    assert isinstance(spec.home(params), dict)
    assert spec.guess is None or isinstance(spec.guess(params), dict)
    assert all(callable(f) for f in spec.scenes.values())
    assert spec.view is None or len(spec.view) == 3
    assert spec.bench_methods, f"{entry.name} declares no bench method of its own"
    assert all(m.quantity in BENCH_QUANTITIES and callable(m.fn) and m.label for m in spec.bench_methods)
    assert all(r.quantity in BENCH_QUANTITIES and callable(r.fn) and r.label for r in spec.bench_references)
    assert spec.self_checks is None or callable(spec.self_checks)
    assert spec.bench_states is None or callable(spec.bench_states)
    assert all(callable(s.run) and s.name and s.condition and s.error for s in spec.failure_studies)
    assert all(
        callable(law.sample) and all(isinstance(j, str) for j in law.reactions) for law in spec.motion_laws.values()
    )
    assert all(callable(m.fn) and m.columns and m.unit and m.doc for m in spec.design_metrics)
    assert all(
        s.doc and callable(s.run) and callable(s.lines) and (s.figures is None or callable(s.figures))
        for s in spec.studies.values()
    )


def test_the_contract_refuses_hooks_it_cannot_use():
    """A spec names its hooks once, and captions or times only the scenes it declares."""
    from mechkit.base.exceptions import InvalidParameters
    from mechkit.catalog.contract import DesignMetric, FailureStudy
    from mechkit.catalog.params import MechanismParams

    base = {
        "name": "m",
        "params": MechanismParams,
        "template": "m.urdf.xacro",
        "actuated": ("a",),
        "gruebler_dof": 1,
        "home": lambda p: {"a": 0.0},
    }
    study = FailureStudy("s", lambda m, quick: [], "condition (-)", "error (-)")
    metric = DesignMetric("d", "-", "a metric", ("d",), lambda m: {"d": 0.0})
    for bad in (
        {"failure_studies": (study, study)},
        {"design_metrics": (metric, metric)},
        {"scene_captions": {"nowhere": "a scene not declared"}},
    ):
        with pytest.raises(InvalidParameters):
            MechanismSpec(**base, **bad)
