"""The pin friction the simulator's friction tests put on the four-bar (not tests themselves)."""

from __future__ import annotations

from mechkit import forces

#: Friction coefficient and pin radius (m) of every pin.
MU, RADIUS = 0.2, 0.01


def friction(m, joints=None) -> forces.ReactionFriction:
    """Friction from the reactions on `joints` (default: every joint, the loop cut included) of mechanism `m`."""
    cm = m.closure_model
    spec = forces.PinFriction(MU, RADIUS)
    return forces.ReactionFriction(
        m.model, cm.joint_names, cm.kernel.cuts, {j: spec for j in (joints or cm.joint_names)}
    )
