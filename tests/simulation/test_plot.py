"""`mechkit.simulation.plot`: the figure of a simulation draws the recorded joints, energy terms and closure
residual (its lines' data are the result's arrays), and is written in the format its suffix names."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.simulation.plot import figure, write_plot


def test_the_panels_draw_the_results_arrays(free):
    import matplotlib.pyplot as plt

    fig = figure(free, "free four-bar")
    try:
        top, mid, bottom = fig.axes
        assert [line.get_label() for line in top.lines] == list(free.motion.coordinates[:12])
        assert np.allclose(top.lines[0].get_ydata(), np.degrees(free.motion.q[:, 0]))
        drawn = {line.get_label(): line.get_ydata() for line in mid.lines}
        assert np.array_equal(drawn["balance drift"], free.balance - free.balance[0])
        assert np.array_equal(drawn["kinetic"], free.kinetic)
        assert np.array_equal(bottom.lines[0].get_ydata(), np.maximum(free.residual, 1e-17))
        assert fig._suptitle.get_text() == "free four-bar"
    finally:
        plt.close(fig)


@pytest.mark.parametrize("suffix, magic", [(".png", b"\x89PNG"), (".svg", b"<?xml"), (".pdf", b"%PDF")])
def test_the_suffix_names_the_format(tmp_path, free, suffix, magic):
    path = write_plot(free, tmp_path / f"free{suffix}")
    assert path.read_bytes().startswith(magic)
