"""The closed-form motion of a planar calibration linkage at a bench sample, and its joint vectors.

A linkage provides its closed form as a `Motion`: (parameters, inputs, rates, accelerations, all in
actuated order) -> `LinkageState` (`mechkit.validation.planar_closed_form`). A bench sample is the
`mechkit bench` one: fields `inputs`, `rates`, `accelerations` (actuated order), `tau` (nv,), and an
`extra` dict where the motion is cached, so the numpy methods' times exclude computing it.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from mechkit.catalog.params import MechanismParams
from mechkit.mechanism import Mechanism
from mechkit.validation.planar_motion import LinkageState

Motion = Callable[[MechanismParams, Sequence[float], Sequence[float], Sequence[float]], LinkageState]
"""(parameters, inputs rad, rates rad/s, accelerations rad/s^2) -> the linkage's exact motion."""


def state(motion: Motion, mech: Mechanism, sample: Any) -> LinkageState:
    """Closed-form motion at the sample's inputs, rates and accelerations (cached in sample.extra).

    Args:
        motion: the linkage's closed form.
        mech: the linkage.
        sample: a bench sample (inputs, rates, accelerations in actuated order; tau; `extra` for the cache).

    Returns:
        The linkage's state.
    """
    if "planar_state" not in sample.extra:
        sample.extra["planar_state"] = motion(mech.params, sample.inputs, sample.rates, sample.accelerations)
    return sample.extra["planar_state"]


def at_rest(motion: Motion, mech: Mechanism, sample: Any) -> LinkageState:
    """Closed-form pose at the sample's inputs, zero rates and accelerations (not cached).

    Args:
        motion: the linkage's closed form.
        mech: the linkage.
        sample: a bench sample (inputs, rates, accelerations in actuated order; tau; `extra` for the cache).

    Returns:
        The linkage's state.
    """
    zero = [0.0] * len(sample.inputs)
    return motion(mech.params, sample.inputs, zero, zero)


def joint_vector(mech: Mechanism, st: LinkageState, values: np.ndarray) -> np.ndarray:
    """Values given on the state's coordinates (`st.coordinates` order) as a mechkit (nv,) vector.

    Args:
        mech: the linkage.
        st: a state of it.
        values: values in `st.coordinates` order.

    Returns:
        (nv,) vector in mechkit's order.
    """
    out = np.zeros(mech.model.nv)
    out[[mech.v_index(j) for j in st.coordinates]] = values
    return out
