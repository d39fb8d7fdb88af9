"""The energy error of a work-precision run, one definition for both codes: the largest drift of the balance
T + V + D (kinetic, potential of gravity and springs, work dissipated since the start) from its start, over
the largest change of any of its three terms.

mechkit's terms are its run's (`SimulationResult`: its dissipated work integrated with the motion). MuJoCo's
are its own energies (`mjENBL_ENERGY`: kinetic, and gravity and springs' potential) at every step, and its
joint dampers' dissipated work by Simpson's rule on their power at every step (a quadrature error of order
dt^4 on a damped model; none on an undamped one).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.integrate import cumulative_simpson


def balance_error(kinetic: np.ndarray, potential: np.ndarray, dissipated: np.ndarray) -> float:
    """The relative drift of the energy balance.

    Args:
        kinetic: (N,) kinetic energy (J) at every sample.
        potential: (N,) potential energy of gravity and springs (J).
        dissipated: (N,) work dissipated since the start, less the work supplied (J).

    Returns:
        max |B - B[0]| / the largest peak-to-peak of the three terms, B = T + V + D.
    """
    balance = kinetic + potential + dissipated
    scale = max(float(np.ptp(x)) for x in (kinetic, potential, dissipated))
    return float(np.max(np.abs(balance - balance[0])) / scale)


def mechkit_energy_error(run: Any) -> float:
    """The relative drift of a mechkit run's energy balance.

    Args:
        run: the `SimulationResult`.

    Returns:
        `balance_error` of its terms.
    """
    potential = run.gravity + run.potentials.sum(axis=1)
    return balance_error(run.kinetic, potential, run.dissipated - run.supplied)


def mujoco_energy_error(model: Any, q0: np.ndarray, steps: int) -> float:
    """The relative drift of a MuJoCo run's energy balance, released at rest at `q0` (a second run: the timed
    one computes no energy).

    Args:
        model: the `mujoco.MjModel` (its timestep and integrator set).
        q0: (nq,) the initial configuration.
        steps: the number of steps.

    Returns:
        `balance_error` of its terms.
    """
    import mujoco

    model.opt.enableflags |= mujoco.mjtEnableBit.mjENBL_ENERGY
    data = mujoco.MjData(model)
    data.qpos[:] = q0
    energy, power = np.empty((steps + 1, 2)), np.empty(steps + 1)
    for k in range(steps + 1):
        mujoco.mj_forward(model, data)
        energy[k], power[k] = data.energy, -data.qfrc_damper @ data.qvel
        if k < steps:
            mujoco.mj_step(model, data)
    dissipated = np.r_[0.0, cumulative_simpson(power, dx=model.opt.timestep)]
    return balance_error(energy[:, 1], energy[:, 0], dissipated)
