"""A state with no rigid answer, which the forward-dynamics and null-space tests share."""

from __future__ import annotations

import numpy as np

from mechkit import core
from mechkit.bench.sampling import make_samples


def inconsistent_state(m):
    """A deployable state whose velocity moves along the freedom that exists only instantaneously: of
    the null-space directions of J (a basis LAPACK chooses), the one farthest off the second-order cone
    relative to its drift; and that distance."""
    s = make_samples(m, 1)[0]
    J = m.closure_jacobian(s.q)
    _, sv, Vt = np.linalg.svd(J)
    null = Vt[core.numerical_rank(sv) :]
    relative = [m.second_order_inconsistency(s.q, v) / np.max(np.abs(m.closure_drift(s.q, v))) for v in null]
    return s.q, null[int(np.argmax(relative))], s.tau, max(relative)
