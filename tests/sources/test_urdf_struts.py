"""`mechkit.sources.urdf_struts`: a `<mechkit:strut>` added to the four-bar's URDF moves the mechanism as the
same `PointToPoint` given from Python does, and a strut that cannot be read is refused by name at load."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import mechkit
from mechkit import forces
from mechkit.base.exceptions import MalformedDescription

STRUT = (
    '<mechkit:strut name="isolator" frame_a="ground" point_a="0.1 0 0.15" frame_b="rocker_link" '
    'point_b="0.11 0 0" stiffness="200" length="0.1" damping="0.5" force="2"/>'
)


def _with(tmp_path, element: str):
    text = (
        (Path(mechkit.__file__).parent / "urdf" / "four_bar.urdf")
        .read_text()
        .replace("</robot>", f"  {element}\n</robot>")
    )
    path = tmp_path / "four_bar_strut.urdf"
    path.write_text(text)
    return path


def test_the_strut_moves_the_mechanism_as_the_python_element(tmp_path, load_cached):
    """0.3 s released at home: the URDF's strut and the Python one give the same motion (1e-12 rad) and the
    file's strut is an element of the run, its potential 100 (L - 0.1)^2 - 2 (L - 0.1)."""
    from_file = mechkit.load(str(_with(tmp_path, STRUT)))
    record = forces.PointToPoint(
        "isolator", "ground", "rocker_link", (0.1, 0, 0.15), (0.11, 0, 0), 200.0, 0.1, 0.5, 2.0
    )
    plain = load_cached("four_bar")
    a = from_file.simulate(0.3, reactions=False)
    b = plain.simulate(0.3, forces=[forces.PointToPointForce(plain.model, record)], reactions=False)
    assert "isolator" in a.element_names
    assert np.ptp(a.motion.q[:, 0]) > 0.05
    assert np.max(np.abs(a.motion.q[-1] - b.motion.q[-1])) < 1e-12


@pytest.mark.parametrize(
    "element, match",
    [
        (STRUT.replace(' length="0.1"', ""), "free length"),
        (STRUT.replace('frame_b="rocker_link"', 'frame_b="no_link"'), "not a link"),
        (STRUT.replace('point_b="0.11 0 0"', 'point_b="0.11 0"'), "three numbers"),
        (STRUT.replace('damping="0.5"', 'damping="-1"'), "damping"),
        (STRUT.replace('force="2"', 'force="nan"'), "not finite"),
        (STRUT.replace('name="isolator" ', ""), "needs a name"),
    ],
)
def test_a_strut_that_cannot_be_read_is_refused_by_name(tmp_path, element, match):
    with pytest.raises(MalformedDescription, match=match):
        mechkit.load(str(_with(tmp_path, element)))
