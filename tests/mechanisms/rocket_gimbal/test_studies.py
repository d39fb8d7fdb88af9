"""`mechkit.mechanisms.rocket_gimbal.studies` and their figures: the linear rule's error map, the
resultant's conditioning, the swing by two methods."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.mechanisms.rocket_gimbal.params import geometry


def test_linearisation_study_finds_the_worst_error_at_a_corner(tmp_path):
    """The linear rule's error map, on a 5 x 5 grid, and its figure."""
    from mechkit.mechanisms.rocket_gimbal.figures import linearisation_figure
    from mechkit.mechanisms.rocket_gimbal.params import RocketGimbalParams
    from mechkit.mechanisms.rocket_gimbal.studies import linearisation, linearisation_summary

    study = linearisation(geometry(RocketGimbalParams()), n=5)
    result = linearisation_summary(study)
    # on a 5 x 5 grid the corners are included: the worst error sits at a corner
    assert 0.4 < result["worst_deg"] < 0.6 and abs(result["worst_at_mm"][0]) == 110.0
    assert np.isclose(result["worst_percent"], 100 * result["worst_deg"] / 6.5)
    [png] = linearisation_figure(study, tmp_path)
    assert png.stat().st_size > 10_000


def test_conditioning_study_reports_the_example_and_the_double_root(tmp_path):
    """The resultant's conditioning: the paper's example, the
    in-range pick, and on the diagonal dlA = dlB a double root, badly conditioned."""
    from mechkit.mechanisms.rocket_gimbal.figures import conditioning_figure
    from mechkit.mechanisms.rocket_gimbal.params import RocketGimbalParams
    from mechkit.mechanisms.rocket_gimbal.studies import conditioning, conditioning_lines

    study = conditioning(geometry(RocketGimbalParams()), n=5)
    text = "\n".join(conditioning_lines(study))
    assert "in-range pick" in text and "double root" in text
    assert np.degrees(study.example.pick.alpha) == pytest.approx(6.629362, abs=1e-6)
    off = study.grid.off_diagonal
    assert np.nanmax(study.grid.condition[~off]) > 1e6 * np.nanmax(study.grid.condition[off])
    [png] = conditioning_figure(study, tmp_path)
    assert png.stat().st_size > 10_000


def test_swing_study_compares_pinocchio_and_soc(mech, tmp_path):
    """One period of the swing by both methods, and its figure."""
    from mechkit.mechanisms.rocket_gimbal.figures import swing_figure
    from mechkit.mechanisms.rocket_gimbal.studies import swing, swing_summary

    study = swing(mech, n=6)
    result = swing_summary(study)
    assert result["worst relative difference Pinocchio vs SOC"] < 1e-8
    assert 1.1 < result["bearing force max (MN)"] < 1.3  # the 1.2 MN thrust plus weight and inertia
    [png] = swing_figure(study, tmp_path)
    assert png.stat().st_size > 10_000
