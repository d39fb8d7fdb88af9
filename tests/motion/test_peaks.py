"""`mechkit.motion.peaks`: peaks against the table's own maxima, axial and radial parts, determinacy."""

from __future__ import annotations

import numpy as np
import pytest

from mechkit import motion
from mechkit.history.result import AXES, COMPONENTS
from mechkit.motion.peaks import QUANTITIES


def test_peaks_are_the_table_maxima(two_t1r):
    _, r = two_t1r
    df = r.to_dataframe()
    peaks = motion.peak_table(r)
    for joint in r.joints:
        f = df[[f"reaction/{joint}/{c}" for c in COMPONENTS[:3]]].to_numpy()
        m = df[[f"reaction/{joint}/{c}" for c in COMPONENTS[3:]]].to_numpy()
        n = df[[f"axis/{joint}/{c}" for c in AXES]].to_numpy()
        for name, vec in (("force", f), ("moment", m)):
            axial = np.abs(np.sum(vec * n, axis=1))
            radial = np.sqrt(np.maximum(np.sum(vec**2, axis=1) - axial**2, 0.0))
            for kind, values in (
                (name, np.linalg.norm(vec, axis=1)),
                (f"axial_{name}", axial),
                (f"radial_{name}", radial),
            ):
                assert peaks.loc[joint, kind] == pytest.approx(values.max(), rel=1e-9, abs=1e-9)
                at_peak = values[(df["t"] == peaks.loc[joint, f"t_{kind}"]).to_numpy()]
                assert at_peak == pytest.approx([values.max()], rel=1e-9, abs=1e-9)
    assert set(QUANTITIES) <= set(peaks.columns)


def test_revolute_axes_carry_no_axial_moment_at_free_hinges(two_t1r):
    """A free revolute hinge transmits no moment about its axis: the axial moment of every unactuated
    tree joint is zero, and the actuated ones carry the efforts."""
    mech, r = two_t1r
    h = motion.peaks(r)
    by_joint = {p.joint: p for p in h}
    scale = np.abs(r.efforts).max()
    for joint in mech.model.names[1:]:
        if joint not in r.actuated:
            assert by_joint[joint].values["axial_moment"] < 1e-9 * scale
    for k, joint in enumerate(r.actuated):
        assert by_joint[joint].values["axial_moment"] == pytest.approx(np.abs(r.efforts[:, k]).max(), rel=1e-9)


def test_peaks_flag_indeterminate_joints(two_t1r):
    """The 2T1R is planar, modelled in space: its out-of-plane reaction parts are indeterminate."""
    _, r = two_t1r
    flags = {p.joint: p.determinate for p in motion.peaks(r)}
    assert set(flags.values()) <= {True, False} and False in flags.values()
    for j, joint in enumerate(r.joints):
        assert flags[joint] == bool(r.determinate[:, j].all())
