"""`mechkit.sources.extended_urdf`: a bad YAML sidecar is a named error."""

from __future__ import annotations

import pytest
from tests_support import FIXTURES

import mechkit
from mechkit.base.exceptions import MalformedDescription


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
