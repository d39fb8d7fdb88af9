"""`mechkit.motion.inputs`: input laws from a function (its derivatives, or differenced), from samples
(a spline) and from a CSV file."""

from __future__ import annotations

import re

import numpy as np
import pytest

from mechkit import motion
from mechkit.base.exceptions import InvalidParameters, MalformedDescription

from .laws import crank_law


def test_callable_differences_and_spline_agree_with_exact_derivatives(load_cached):
    mech = load_cached("four_bar")
    t = np.linspace(0.0, 3.0, 301)
    exact = motion.from_callable(mech, crank_law, t)
    differenced = motion.from_callable(mech, lambda x: crank_law(x)[0], t)
    assert np.allclose(differenced.rates, exact.rates, atol=1e-9)
    assert np.allclose(differenced.accelerations, exact.accelerations, atol=1e-6)
    splined = motion.from_arrays(mech, t, exact.values[:, 0])
    inner = slice(10, -10)  # not-a-knot ends are less accurate
    assert np.allclose(splined.rates[inner], exact.rates[inner], atol=1e-6)
    assert np.allclose(splined.accelerations[inner], exact.accelerations[inner], atol=1e-3)


def test_csv_law(load_cached, tmp_path):
    mech = load_cached("four_bar")
    exact = motion.from_callable(mech, crank_law, np.linspace(0.0, 1.0, 5))
    path = tmp_path / "law.csv"
    rows = ["t,crank,crank_dot,crank_ddot"] + [
        f"{float(t)!r},{float(x[0])!r},{float(v[0])!r},{float(a[0])!r}"
        for t, x, v, a in zip(exact.t, exact.values, exact.rates, exact.accelerations)
    ]
    path.write_text("# a crank swing\n" + "\n".join(rows) + "\n")
    law = motion.from_csv(mech, path)
    assert law.names == ("crank",)
    for field in ("t", "values", "rates", "accelerations"):
        assert np.array_equal(getattr(law, field), getattr(exact, field))


@pytest.mark.parametrize(
    "text, needle",
    [
        ("crank\n0.1\n0.2\n", "'t' column"),
        ("t,crank\n0,0.6\n1,x\n", "not a number"),
        ("t,crank\n0,0.6\n0,0.7\n1,0.8\n2,0.9\n", "strictly increasing"),
        ("t,wheel\n0,0.6\n1,0.7\n2,0.8\n3,0.9\n", "'wheel'"),
        (
            "# law\nt,crank\n0,0.6\n1,0.7\n\n2,nan\n3,0.9\n",
            "law.csv: line 6: column 'crank': 'nan' is not a finite number",
        ),
        ("t,crank\n0,0.6\n1,inf\n2,0.8\n3,0.9\n", "line 3: column 'crank': 'inf' is not a finite number"),
        ("t,crank,crank_dot,crank_ddot\n0,0.6,0,0\n1,0.7,nan,0\n", "line 3: column 'crank_dot'"),
        ("t,crank\n0,0.6\n1,\n2,0.8\n3,0.9\n", "line 3: column 'crank': '' is not a number"),
        ("t,crank\n0,0.6\n1,0.7,0\n2,0.8\n3,0.9\n", "line 3: 3 cells, the header has 2"),
        ("t,crank,crank\n0,0.6,0\n1,0.7,0\n2,0.8,0\n", "column 'crank' is given twice"),
        ("t,crank,\n0,0.6,0\n1,0.7,0\n2,0.8,0\n", "column '' is empty"),
        ("t,x_dot\n0,0.6\n1,0.7\n2,0.8\n", "a column per driven joint besides 't'"),
        ("t,crank,crank_dot\n0,0.6,0\n1,0.7,0\n2,0.8,0\n", "(crank_ddot): give <joint>_dot and <joint>_ddot"),
        ("t,crank,rocker_dot\n0,0.6,0\n1,0.7,0\n2,0.8,0\n", "(rocker_dot): give"),
    ],
)
def test_bad_csv_law_is_a_named_error(load_cached, tmp_path, text, needle):
    path = tmp_path / "law.csv"
    path.write_text(text)
    with pytest.raises((InvalidParameters, MalformedDescription), match=re.escape(needle)):
        motion.from_csv(load_cached("four_bar"), path)


def test_a_law_that_is_not_text_is_named(load_cached, tmp_path):
    """A binary file given as a law was a UnicodeDecodeError traceback."""
    path = tmp_path / "law.csv"
    path.write_bytes(b"t,crank\n0,\xf0\x28\x8c\x28\n")
    with pytest.raises(MalformedDescription, match="cannot read the input law: not a text file"):
        motion.from_csv(load_cached("four_bar"), path)
