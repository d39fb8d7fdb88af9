"""The paper's gimbal at its default geometry, and its worked example: strokes {-60, 105} mm, its FK
answer, and its IK of that answer as strokes."""

from __future__ import annotations

import numpy as np

from mechkit.mechanisms.rocket_gimbal.kinematics import PAPER_EXAMPLE
from mechkit.mechanisms.rocket_gimbal.params import RocketGimbalParams, geometry

GEO = geometry(RocketGimbalParams())
MM = 1e-3
PAPER_STROKES, PAPER_ANGLES = PAPER_EXAMPLE["strokes"], PAPER_EXAMPLE["angles"]
PAPER_IK = np.array([-60.1145, 104.9909]) * MM
