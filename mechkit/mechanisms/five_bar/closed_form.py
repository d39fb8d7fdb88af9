"""The five-bar's closed form (`mechkit.validation.planar_closed_form.five_bar`) at its parameters."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import fields

from mechkit.mechanisms.five_bar.params import FiveBarParams
from mechkit.validation.planar_closed_form import FiveBarGeometry, five_bar
from mechkit.validation.planar_motion import LinkageState


def geometry(params: FiveBarParams) -> FiveBarGeometry:
    """The reference geometry (lengths m, bar section m, density kg/m^3) of these parameters.

    Args:
        params: the linkage's parameters.

    Returns:
        The geometry of `mechkit.validation.planar_closed_form`.
    """
    return FiveBarGeometry(**{f.name: getattr(params, f.name) for f in fields(FiveBarGeometry)})


def motion(
    params: FiveBarParams, inputs: Sequence[float], rates: Sequence[float], accelerations: Sequence[float]
) -> LinkageState:
    """Exact motion from both proximal angles (rad), rates (rad/s) and accelerations (rad/s^2), C up.

    Args:
        params: the linkage's parameters.
        inputs: the actuated angles (rad), in actuated order.
        rates: their rates (rad/s).
        accelerations: their accelerations (rad/s^2).

    Returns:
        The linkage's state.
    """
    return five_bar(tuple(inputs), tuple(rates), tuple(accelerations), geometry(params))
