"""What the export tests share: the mechanisms exported and read back, and a pose away from home."""

from __future__ import annotations

import numpy as np
import pinocchio as pin

#: Mechanisms whose exports are read back by MuJoCo and Pinocchio (a planar, a spatial and two
#: spherical-cut linkages).
NAMES = ["four_bar", "five_bar", "rocket_gimbal", "spherical_2dof"]


def other_pose(m) -> np.ndarray:
    """An assembled configuration away from home (the one the MJCF is written at)."""
    home = np.array([m.home_q[m.q_index(j)] for j in m.actuated])
    return m.assemble(home + 0.02, guess=m.home_q)


def load_extended_urdf(urdf: str, yaml_text: str) -> tuple[pin.Model, list[pin.RigidConstraintModel], list[str]]:
    """An independent reader for the round trip: an Extended URDF pair read the way Gepetto's loader does
    (model, RigidConstraintModels, motors), for pairs without substitutions (mechkit's exports).

    Every pair is a point (3d) or frame (6d) anchor, as in Gepetto's toolbox; `read_extended_urdf`
    is mechkit's reading (joints, not anchors).

    Args:
        urdf: tree URDF text.
        yaml_text: sidecar text (`closed_loop`, `type`, `name_mot`).

    Returns:
        (the tree model, one RigidConstraintModel per pair (LOCAL frames), the motors' joint names).
    """
    import yaml

    content = yaml.safe_load(yaml_text)
    model = pin.buildModelFromXML(urdf)
    constraints = []
    for (name_a, name_b), kind in zip(content["closed_loop"], content["type"], strict=True):
        fa, fb = (model.frames[model.getFrameId(n)] for n in (name_a, name_b))
        contact = pin.ContactType.CONTACT_3D if kind.lower() == "3d" else pin.ContactType.CONTACT_6D
        constraints.append(
            pin.RigidConstraintModel(
                contact, model, fa.parentJoint, fa.placement, fb.parentJoint, fb.placement, pin.ReferenceFrame.LOCAL
            )
        )
    return model, constraints, list(content["name_mot"])
