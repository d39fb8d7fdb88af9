"""`mechkit modes`: the natural frequencies printed are the elastic model's at the pose asked for, in JSON
and as text; a bad count is refused in one line naming the option."""

from __future__ import annotations

import json

import numpy as np
import pytest

from mechkit.cli import main


def test_the_frequencies_are_the_elastic_models_at_the_pose(load_cached, capsys):
    from mechkit.elastic import ElasticModel

    m = load_cached("four_bar")
    assert main(["modes", "four_bar", "-n", "3", "--at", "crank=0.8", "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    modes = ElasticModel(m).modes(m.assemble({"crank": 0.8}), 3)
    assert [x["mode"] for x in r["modes"]] == [1, 2, 3] and r["animation"] is None
    assert np.allclose([x["frequency_hz"] for x in r["modes"]], modes.frequencies, rtol=1e-9)
    for x, shape in zip(r["modes"], modes.shapes):
        assert x["largest_motion_body"] == modes.names[int(np.abs(shape[:, :3]).sum(axis=1).argmax())]
    assert main(["modes", "four_bar", "-n", "2"]) == 0
    text = capsys.readouterr().out.splitlines()
    home = ElasticModel(m).modes(m.home_q, 2)
    assert text[0] == "four_bar: natural frequencies, actuators locked" and len(text) == 3
    assert text[1].startswith(f"  mode 1: {home.frequencies[0]:.4g} Hz")


@pytest.mark.parametrize("n", ["0", "-2"])
def test_a_bad_count_is_refused_in_one_line(capsys, n):
    assert main(["modes", "four_bar", "-n", n]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mechkit: error:") and "'-n'" in err and err.count("\n") == 1


def test_a_mode_without_an_animation_is_refused(capsys):
    """`--mode` chooses what --animate shows: alone it was ignored in silence."""
    assert main(["modes", "four_bar", "--mode", "2"]) == 2
    err = capsys.readouterr().err
    assert (
        err.startswith("mechkit: error: argument '--mode': chooses the mode --animate shows") and err.count("\n") == 1
    )
