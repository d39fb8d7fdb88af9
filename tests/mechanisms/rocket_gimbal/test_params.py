"""`mechkit.mechanisms.rocket_gimbal.params`: the URDF's inertias are the Python body inertias."""

from __future__ import annotations

import numpy as np

from mechkit.mechanisms.rocket_gimbal.params import body_inertias


def test_urdf_inertias_are_the_python_body_inertias(mech):
    model = mech.model
    for body, (mass, transverse, axial) in body_inertias(mech.params).items():
        frame = model.frames[model.getFrameId(body)]
        inertia = model.inertias[frame.parentJoint]
        assert np.isclose(inertia.mass, mass, rtol=1e-12)
        assert np.allclose(
            np.sort(np.linalg.eigvalsh(inertia.inertia)), np.sort([transverse, transverse, axial]), rtol=1e-12
        )
