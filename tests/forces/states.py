"""The state the force elements' tests evaluate them at (not tests themselves)."""

from __future__ import annotations

from mechkit import forces


def state(m, q=None, v=None, t=0.0) -> forces.ForceState:
    """The four-bar's `ForceState` at crank 0.9 rad turning at 1.5 rad/s, unless q or v are given."""
    q = m.assemble([0.9]) if q is None else q
    v = m.velocities(q, [1.5]) if v is None else v
    return forces.ForceState.at(m.model, m.model.createData(), q, v, t)
