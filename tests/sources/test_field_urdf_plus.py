"""URDF+'s authors' example models (generalized_rbda) through `mechkit report` (the command line, JSON),
against the independent reading of `independent.urdf_plus_load` at the configuration the report holds:
DOF (the four-bar is written at its flat pose, where a parallelogram has two freedoms), and the files
mechkit refuses, each in one line: a planar body written with izz alone (no body has that inertia). The
six-bar is written flat with its loop open by 0.3 m along the links, where the closure residual is
stationary (the rows' Jacobian has no component along the gap): the assembly restarts from seeded
perturbations (`mechkit.core.assembly`) and closes it."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from .field_cli import refusal, report
from .independent import require_closed, study, urdf_plus_load

FIELD = Path(__file__).resolve().parents[1] / "fixtures" / "field" / "urdf_plus"
#: file -> its DOF at the report's home
REPORTED = {
    "four_bar.urdf": 2,
    "six_bar.urdf": 3,
    "mit_humanoid.urdf": 24,
    "revolute_rotor_chain.urdf": 3,
    "mit_humanoid_leg.urdf": 5,
}
REFUSED = {"planar_leg_linkage.urdf": "link 'thigh': inertia", "mini_cheetah_leg.urdf": "link 'abduct': inertia"}


def test_every_fixture_is_reported_or_refused():
    assert sorted(p.name for p in FIELD.glob("*.urdf")) == sorted([*REPORTED, *REFUSED])


@pytest.mark.parametrize("file", list(REPORTED))
def test_the_report_agrees_with_the_independent_reading(file):
    r = report(FIELD / file)
    model, cuts, couplings, _ = urdf_plus_load(FIELD / file)
    q = np.array(r["home_q"])
    require_closed(file, model, cuts, q)
    assert r["dof"] == study(model, cuts, [], q, couplings=couplings).dof == REPORTED[file]
    assert r["holding"] == {"refused": "unactuated: no actuator to hold it"}  # URDF+ declares no motor


@pytest.mark.parametrize("file", list(REFUSED))
def test_the_files_mechkit_cannot_load_are_refused_in_one_line(file):
    assert REFUSED[file] in refusal(FIELD / file)
