"""A planar calibration linkage in Lagrange's equations of the first kind (`mechkit.validation.lagrange`).

Reference-point coordinates: x, z (m) and phi (rad) of every link's centre of mass; every pin, the
loop cut "C" included, gives two rows of C_q. Inverse dynamics is the ten-bar patent's A f = P
(efforts and in-plane pin forces); forward dynamics solves the augmented system for the accelerations.
Both start from the sample's closed-form link motion (`state.state`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechkit.mechanism import Mechanism
from mechkit.mechanisms.planar_linkage.state import Motion, joint_vector, state
from mechkit.validation import lagrange


def lagrange_problem(
    motion: Motion, mech: Mechanism, sample: Any
) -> tuple[lagrange.Linkage, np.ndarray, np.ndarray, list[float]]:
    """The linkage in reference-point coordinates and its state (q, qd, motor accelerations); cached.

    Args:
        motion: the linkage's closed form.
        mech: the linkage.
        sample: a bench sample (inputs, rates, accelerations in actuated order; tau; `extra` for the cache).

    Returns:
        (the linkage in `mechkit.validation.lagrange`, q, qd (3 per link), motor accelerations (rad/s^2)).
    """
    if "lagrange" not in sample.extra:
        st = state(motion, mech, sample)
        names = list(st.links)
        bodies = [
            lagrange.Body(
                n, st.links[n].bar.mass, st.links[n].bar.inertia_planar, np.array([st.links[n].bar.length / 2.0, 0.0])
            )
            for n in names
        ]
        pins = []
        for j in st.joints:
            b = names.index(j.child)
            point_b = (st.links[j.child].bar.length if j.name == "C" else 0.0) * np.array([1.0, 0.0])
            if j.parent is None:
                pins.append(lagrange.Pin(j.name, None, j.point, b, point_b))
            else:
                pins.append(
                    lagrange.Pin(
                        j.name, names.index(j.parent), np.array([st.links[j.parent].bar.length, 0.0]), b, point_b
                    )
                )
        motors = [j.name for j in st.joints if j.actuated]
        linkage = lagrange.Linkage(bodies, pins, motors)
        q = np.concatenate([[*st.links[n].com, st.links[n].angle] for n in names])
        qd = np.concatenate([[*st.links[n].com_velocity, st.links[n].omega] for n in names])
        acc = [st.links[m].alpha for m in motors]  # grounded motors: relative = absolute
        sample.extra["lagrange"] = (linkage, q, qd, acc)
    return sample.extra["lagrange"]


def lagrange_first_kind(motion: Motion, mech: Mechanism, sample: Any) -> dict[str, Any]:
    """Efforts (N m) and pin forces (in-plane, world wrenches (6,)) from the patent's A f = P.

    Args:
        motion: the linkage's closed form.
        mech: the linkage.
        sample: a bench sample (inputs, rates, accelerations in actuated order; tau; `extra` for the cache).

    Returns:
        {"efforts": motor -> torque (N m), "reactions": pin -> world wrench (6,)}.
    """
    linkage, q, qd, acc = lagrange_problem(motion, mech, sample)
    sol = linkage.solve(q, qd, acc)
    reactions = {}
    for name, f in sol.forces.items():
        reactions[name] = np.array([f[0], 0.0, f[1], 0.0, 0.0, 0.0])
    return {"efforts": sol.efforts, "reactions": reactions}


def lagrange_forward(motion: Motion, mech: Mechanism, sample: Any) -> np.ndarray:
    """Forward dynamics in reference-point coordinates (`mechkit.validation.lagrange.Linkage.forward`).

    The efforts u are the sample's tau on the motor pins (torques about -y); returns the joint
    accelerations of mechkit's q (relative angle rates of each URDF joint).

    Args:
        motion: the linkage's closed form.
        mech: the linkage.
        sample: a bench sample (inputs, rates, accelerations in actuated order; tau; `extra` for the cache).

    Returns:
        a (nv,), rad/s^2.
    """
    linkage, q, qd, _ = lagrange_problem(motion, mech, sample)
    st = state(motion, mech, sample)
    x = linkage.forward(q, qd, [sample.tau[mech.v_index(j)] for j in linkage.motors])
    names = list(st.links)
    alpha = {name: x[3 * i + 2] for i, name in enumerate(names)}
    joint_acc = [alpha[j.child] - (alpha[j.parent] if j.parent else 0.0) for j in (st.joint(c) for c in st.coordinates)]
    return joint_vector(mech, st, np.array(joint_acc))
