"""`mechkit.mechanisms.parallel_2t1r.checks`: the report rows."""

from __future__ import annotations

import numpy as np

from mechkit.mechanisms.parallel_2t1r import SPEC


def test_self_checks_report(mech):
    checks = SPEC.self_checks(mech)
    assert checks and all(np.isfinite(x) and x < 1e-8 for x in checks.values())
