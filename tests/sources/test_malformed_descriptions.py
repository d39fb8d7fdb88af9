"""The bad-input campaign on descriptions (hypothesis): the catalogue's and the fixtures' files with one element
deleted or one number replaced by NaN, inf, a negative, zero, a huge value or text. Whatever is drawn, loading
and reporting either give a mechanism whose results are finite and whose report is strict JSON, or refuse with a
named `MechkitError`; never another exception, never a NaN passed off as a result. (A crash inside Pinocchio
would end this process: `tests/core/test_pin_constraints.py` runs the entry points in a subprocess.)"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from tests_support import FIXTURES, ROOT

import mechkit
from mechkit.base.exceptions import MechkitError
from mechkit.base.json_text import dumps
from mechkit.report import report

SOURCES = [
    ROOT / "urdf" / "four_bar.urdf",
    ROOT / "urdf" / "five_bar.urdf",
    ROOT / "urdf" / "spherical_2dof.urdf",
    FIXTURES / "slider_crank.urdf",
    FIXTURES / "rssr.xml",
    FIXTURES / "field" / "sdf" / "four_bar_gearbox.sdf",
]
TEXTS = {path: path.read_text() for path in SOURCES}
BAD = ["nan", "inf", "-inf", "-1", "0", "1e300", "-1e-300", "abc", ""]
NUMERIC = re.compile(r"^[-+0-9.eE ]+$")


def _elements(root: ET.Element) -> list[ET.Element]:
    return list(root.iter())


@st.composite
def malformed(draw):
    """(suffix, text, what was done) of one source with one mutation."""
    path = draw(st.sampled_from(SOURCES))
    root = ET.fromstring(TEXTS[path])
    parents = {child: parent for parent in root.iter() for child in parent}
    if draw(st.booleans()):
        element = draw(st.sampled_from([e for e in _elements(root) if e in parents]))
        parents[element].remove(element)
        what = f"deleted <{element.tag}>"
    else:
        numeric = [(e, a) for e in _elements(root) for a, v in e.attrib.items() if NUMERIC.match(v)]
        numeric += [(e, None) for e in _elements(root) if e.text and NUMERIC.match(e.text.strip())]
        element, attribute = draw(st.sampled_from(numeric))
        values = (element.get(attribute) if attribute else element.text).split()
        k = draw(st.integers(0, len(values) - 1))
        values[k] = draw(st.sampled_from(BAD))
        if attribute:
            element.set(attribute, " ".join(values))
        else:
            element.text = " ".join(values)
        what = f"<{element.tag}> {attribute or 'text'}[{k}] = {values[k]!r}"
    return "".join(path.suffixes), ET.tostring(root, encoding="unicode"), f"{path.name}: {what}"


@pytest.mark.filterwarnings("ignore::mechkit.base.exceptions.MuJoCoWarning")  # said, as it should be
@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(case=malformed())
def test_a_malformed_description_is_refused_by_name_or_gives_finite_results(tmp_path, case):
    suffix, text, what = case
    path = tmp_path / f"case{suffix}"
    path.write_text(text)
    try:
        with np.errstate(all="raise", under="ignore"):  # as the command line runs: an overflow is a failure
            m = mechkit.load(path)
            r = report(m)
    except MechkitError:
        return  # refused by name
    except Exception as err:  # noqa: BLE001 - the campaign's finding, shown with what was drawn
        pytest.fail(f"{what}: {type(err).__name__}: {err}")
    assert np.all(np.isfinite(m.home_q)), what
    dumps(r)  # strict JSON: a non-finite number would be refused here
