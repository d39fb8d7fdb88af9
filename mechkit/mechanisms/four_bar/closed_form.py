"""The four-bar's closed form (`mechkit.validation.planar_closed_form.four_bar`) at its parameters."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import fields

from mechkit.mechanisms.four_bar.params import FourBarParams
from mechkit.validation.planar_closed_form import FourBarGeometry, four_bar
from mechkit.validation.planar_motion import LinkageState


def geometry(params: FourBarParams) -> FourBarGeometry:
    """The reference geometry (lengths m, bar section m, density kg/m^3) of these parameters.

    Args:
        params: the linkage's parameters.

    Returns:
        The geometry of `mechkit.validation.planar_closed_form`.
    """
    return FourBarGeometry(**{f.name: getattr(params, f.name) for f in fields(FourBarGeometry)})


def motion(
    params: FourBarParams, inputs: Sequence[float], rates: Sequence[float], accelerations: Sequence[float]
) -> LinkageState:
    """Exact motion from the crank's angle (rad), rate (rad/s) and acceleration (rad/s^2), open branch.

    Args:
        params: the linkage's parameters.
        inputs: the actuated angles (rad), in actuated order.
        rates: their rates (rad/s).
        accelerations: their accelerations (rad/s^2).

    Returns:
        The linkage's state.
    """
    return four_bar(inputs[0], rates[0], accelerations[0], geometry(params))
