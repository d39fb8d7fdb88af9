"""The node centres of a truss model (frames `node_<X>`), read by Pinocchio forward kinematics."""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import InvalidParameters
from mechkit.mechanism import Mechanism

#: Node letters of the composite (the unit has A, B, E, H).
NODES = ("A", "B", "C", "D", "E", "F", "G", "H", "I", "J")


def node_positions(mech: Mechanism, q: np.ndarray) -> dict[str, np.ndarray]:
    """World positions (m) of the node centres in the model at q (Pinocchio forward kinematics).

    Args:
        mech: `tetra_3rr3uru` or `deployable_9rr12uru`.
        q: a configuration (nq,).

    Returns:
        Node letter -> position (3,), m.
    """
    pin.forwardKinematics(mech.model, mech.data, q)
    pin.updateFramePlacements(mech.model, mech.data)
    out = {}
    for node in NODES:
        name = f"node_{node}"
        if mech.model.existFrame(name):
            out[node] = mech.data.oMf[mech.model.getFrameId(name)].translation.copy()
    return out


def node_velocity(mech: Mechanism, q: np.ndarray, v: np.ndarray, node: str) -> np.ndarray:
    """World velocity (m/s) of a node centre in the model at (q, v).

    Args:
        mech: `tetra_3rr3uru` or `deployable_9rr12uru`.
        q: a configuration (nq,).
        v: a velocity (nv,).
        node: a node letter.

    Returns:
        (3,) velocity, m/s.

    Raises:
        InvalidParameters: no such node in the model.
    """
    frame = f"node_{node}"
    if not mech.model.existFrame(frame):
        raise InvalidParameters("node", node, f"no node {node} in {mech.spec.name}")
    pin.forwardKinematics(mech.model, mech.data, q, v)
    velocity = pin.getFrameVelocity(
        mech.model, mech.data, mech.model.getFrameId(frame), pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
    )
    return velocity.linear.copy()
