"""`mechkit stiffness`: the 6x6 compliance and stiffness printed are the elastic model's at the body, point
and pose asked for (held K_ii, free 1/C_ii); an unknown link or a bad point is refused in one line."""

from __future__ import annotations

import json

import numpy as np
import pytest

from mechkit.cli import main


def test_the_2t1r_platform_is_stiffer_held_than_free(capsys):
    assert main(["stiffness", "parallel_2t1r", "--body", "platform", "--at", "R11=0.2,R21=0.35,R31=0.5", "--json"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["held"]["y"] >= s["free"]["y"] > 0


def test_the_json_is_the_elastic_models_stiffness(load_cached, capsys):
    """The four-bar's coupler at a point off its origin: the compliance is the model's, symmetric and
    positive semi-definite; free is 1/C_ii and held the stiffness' diagonal (None where infinite)."""
    from mechkit.elastic import ElasticModel

    m = load_cached("four_bar")
    assert (
        main(["stiffness", "four_bar", "--body", "coupler_link", "--point", "0.14,0,0", "--at", "crank=0.8", "--json"])
        == 0
    )
    r = json.loads(capsys.readouterr().out)
    s = ElasticModel(m).stiffness(m.assemble({"crank": 0.8}), "coupler_link", [0.14, 0.0, 0.0])
    C = np.array(r["compliance"])
    assert np.allclose(C, s.compliance, rtol=1e-12, atol=0.0) and np.allclose(C, C.T, atol=1e-12 * np.abs(C).max())
    assert np.linalg.eigvalsh(C).min() > -1e-9 * np.abs(C).max()
    assert np.allclose(r["point"], s.point)
    directions = ("x", "y", "z", "rx", "ry", "rz")
    soft = np.diag(C) > 0
    assert np.allclose([r["free"][d] for d, k in zip(directions, soft) if k], 1 / np.diag(C)[soft], rtol=1e-9)
    K = np.array([[np.inf if x is None else x for x in row] for row in r["stiffness"]])
    assert np.allclose([r["held"][d] for d in directions], np.diag(K), rtol=1e-12)


def test_the_text_has_one_line_per_direction(capsys):
    assert main(["stiffness", "four_bar", "--body", "coupler_link"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("four_bar: body coupler_link at (") and len(lines) == 8
    assert [line.split()[0] for line in lines[2:]] == ["x", "y", "z", "rx", "ry", "rz"]


@pytest.mark.parametrize(
    "args, message",
    [
        (["--body", "nowhere"], "no such link"),
        (["--body", "coupler_link", "--point", "0.1,0"], "'--point'"),
        (["--body", "coupler_link", "--at", "nope=1"], "error: --at: 'nope' is neither a joint nor an actuator"),
    ],
)
def test_bad_input_is_refused_in_one_line(capsys, args, message):
    assert main(["stiffness", "four_bar", *args]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mechkit: error:") and message in err and err.count("\n") == 1


def test_a_body_held_rigidly_has_null_stiffness_with_the_reason_never_infinity(tmp_path, capsys):
    """The four-bar with its crank's beam removed: the crank, on its locked actuator, yields in no direction.
    JSON used to carry Infinity (not JSON); text printed inf."""
    import json
    import re

    from tests_support import ROOT

    from mechkit.cli import main

    text = (ROOT / "urdf" / "four_bar.urdf").read_text()
    path = tmp_path / "rigid_crank.urdf"
    path.write_text(re.sub(r'  <mechkit:beam [^>]*link="crank_link"/>\n', "", text))
    assert main(["stiffness", str(path), "--actuated", "crank", "--body", "crank_link", "--json"]) == 0
    r = json.loads(capsys.readouterr().out, parse_constant=lambda c: pytest.fail(f"{c} in JSON"))
    assert len(r["rigid_directions"]) == 6 and set(r["held"].values()) == {None} == set(r["free"].values())
    assert set(r["held_why"]) == set(r["held"]) and r["held_why"]["x"].startswith("held rigidly")
    assert main(["stiffness", str(path), "--actuated", "crank", "--body", "crank_link"]) == 0
    out = capsys.readouterr().out
    assert "rigid" in out and not re.search(r"\b(inf|nan)\b", out, re.IGNORECASE)
