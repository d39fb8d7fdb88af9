"""The 2T1R's own methods in `mechkit bench` (`SPEC.bench_methods`, `SPEC.bench_references`).

Assembly: the paper's position analysis (the five-bar's C1 by eq. (7), limbs II and III closed in
turn, on the assembled branch), then the joint coordinates in closed form. Inverse dynamics: SOC
over the paper's three SKCs and the classic whole-mechanism virtual work (torques only), both from
the analytic motion state of the sample's motor angles, rates and accelerations (eqs. (7)-(9),
(12), (15), cached in `sample.extra`: their times exclude it). SOC is also the independent
reference. The methods drive the paper's three motors (R11, R21, R31).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from mechkit.catalog.contract import BenchMethod, BenchReference
from mechkit.mechanisms.parallel_2t1r.branch import INPUTS, assembled_pose
from mechkit.mechanisms.parallel_2t1r.joint_state import configuration
from mechkit.mechanisms.parallel_2t1r.motion_law import state_at
from mechkit.mechanisms.parallel_2t1r.rates import State, at_rest
from mechkit.mechanisms.parallel_2t1r.soc import classic_torques, soc_inverse_dynamics
from mechkit.validation.soc import SOCResult

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

__all__ = ["METHODS", "REFERENCES"]


def _motors(mech: Mechanism, x: np.ndarray, index: str = "v") -> np.ndarray:
    """The three motors' entries of a joint vector (q with index "q", v or a with "v")."""
    at = mech.q_index if index == "q" else mech.v_index
    return np.array([x[at(j)] for j in INPUTS])


def analytic_state(mech: Mechanism, sample: Any) -> State:
    """The paper's motion state at the sample's motor angles, rates and accelerations; cached.

    Args:
        mech: the 2T1R.
        sample: a bench sample (motor angles, rates, accelerations; `extra` for the cache).

    Returns:
        The analytic state.
    """
    if "2t1r_state" not in sample.extra:
        sample.extra["2t1r_state"] = state_at(
            mech.params, _motors(mech, sample.q, "q"), _motors(mech, sample.v), _motors(mech, sample.a)
        )
    return sample.extra["2t1r_state"]


def paper_fk(mech: Mechanism, sample: Any) -> np.ndarray:
    """Assembly by the paper's position analysis on the assembled branch, as a mechkit q (rad).

    Args:
        mech: the 2T1R.
        sample: a bench sample (motor angles, rates, accelerations; `extra` for the cache).

    Returns:
        q (nq,).
    """
    theta = _motors(mech, sample.q, "q")
    pose, theta4, _ = assembled_pose(mech.params.dims, theta)
    return configuration(mech, at_rest(pose, theta, theta4))


def soc(mech: Mechanism, sample: Any) -> SOCResult:
    """SOC virtual work over the three SKCs: motor torques and the reactions at R23 and R43.

    Args:
        mech: the 2T1R.
        sample: a bench sample (motor angles, rates, accelerations; `extra` for the cache).

    Returns:
        Efforts (N m) and the reactions at R23 and R43 (world wrenches (6,)).
    """
    return soc_inverse_dynamics(mech.params, analytic_state(mech, sample))


def classic(mech: Mechanism, sample: Any) -> dict[str, Any]:
    """Classic whole-mechanism virtual work, eqs. (39)-(40): motor torques only.

    Args:
        mech: the 2T1R.
        sample: a bench sample (motor angles, rates, accelerations; `extra` for the cache).

    Returns:
        {"efforts": motor -> torque (N m)}.
    """
    return {"efforts": classic_torques(mech.params, analytic_state(mech, sample))[0]}


METHODS = (
    BenchMethod("paper FK (eqs. 7-9) + closed-form joints", "assembly", paper_fk),
    BenchMethod("SOC, 3 SKCs (numpy, from the analytic state)", "inverse_dynamics", soc),
    BenchMethod("classic virtual work (numpy, from the analytic state)", "inverse_dynamics", classic),
)
REFERENCES = (BenchReference("SOC over the paper's three SKCs (numpy, analytic motion)", "inverse_dynamics", soc),)
