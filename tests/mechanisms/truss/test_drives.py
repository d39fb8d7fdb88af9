"""`mechkit.mechanisms.truss.drives`: the drive laws of section 3.2."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanisms.truss.drives import drive_state
from mechkit.mechanisms.truss.geometry import (
    DEG,
    GAMMA0,
)


def test_gamma_law_sign_reading_gives_the_printed_gamma0():
    assert drive_state(0.0).gamma == pytest.approx(GAMMA0, abs=5e-4 * DEG)  # printed to 0.001 deg
    gammas = [drive_state(t).gamma for t in np.linspace(0, 200, 41)]
    assert max(gammas) < 0.0


@pytest.mark.parametrize("t", (1.0, 80.0, 199.0))
def test_drive_derivatives_against_differences(t):
    h = 1e-3
    lo, mid, hi = (drive_state(min(max(x, 0.0), 200.0)) for x in (t - h, t, t + h))
    span = min(t + h, 200.0) - max(t - h, 0.0)
    assert mid.alpha_rate == pytest.approx((hi.alpha - lo.alpha) / span, rel=1e-6)
    assert mid.gamma_rate == pytest.approx((hi.gamma - lo.gamma) / span, rel=1e-6)
    assert mid.alpha_acc == pytest.approx((hi.alpha_rate - lo.alpha_rate) / span, rel=1e-5)
    assert mid.gamma_acc == pytest.approx((hi.gamma_rate - lo.gamma_rate) / span, rel=1e-5, abs=1e-12)


@pytest.mark.parametrize("bad", [{"t": -1.0}, {"t": 201.0}, {"t": float("nan")}])
def test_drive_laws_refuse_times_outside_the_fold(bad):
    with pytest.raises(InvalidParameters, match="t"):
        drive_state(**bad)
