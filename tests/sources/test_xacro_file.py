"""`mechkit.sources.xacro_file`: keyword parameters are xacro arguments; unknown ones, and parameters
given to a file that is not xacro, are named errors."""

from __future__ import annotations

import numpy as np
import pytest
from tests_support import FIXTURES

import mechkit
from mechkit.base.exceptions import InvalidParameters, MalformedDescription
from mechkit.report import report


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


def test_xacro_errors(tmp_path):
    with pytest.raises(InvalidParameters, match="no such xacro:arg"):
        mechkit.load(FIXTURES / "watt_six_bar.urdf.xacro", thet=1.0)
    with pytest.raises(InvalidParameters, match="not a xacro file"):
        mechkit.load(FIXTURES / "slider_crank.urdf", crank=0.2)
    with pytest.raises(MalformedDescription):
        mechkit.load(FIXTURES / "watt_six_bar.urdf.xacro", theta=3.0, b=0.01)  # the circles do not meet
