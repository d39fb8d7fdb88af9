"""Coupling rows: a coupling (`mechkit.core.records.Coupling`) resolved on a model, and its one row on
joint values, for one sample or any leading sample axes.

A coupling row reads the values x of one-freedom joints (a continuous joint's value is the angle of its
two coordinates): e = f . x - f_ref - P(s) with s = l . x - l_ref, f the followers' coefficients, l the
leaders', P a polynomial; Jacobian f - P'(s) l on the joints' velocity columns; drift -P''(s) (l . v)^2,
so that d2e/dt2 = J a + gamma. The closure kernel (`mechkit.core.kernel`) puts these rows after its cut
rows.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import MalformedDescription
from mechkit.core.records import Coupling


@dataclass(frozen=True)
class CouplingRow:
    """One coupling resolved on a model: e = f . x - follower_ref - P(l . x - leader_ref).

    Attributes:
        coupling: the declaration.
        q_index, v_index: (k,) configuration and velocity indices of the joints it names (followers
            first), one-freedom joints only.
        unbounded: (k,) True where the joint is continuous (its value is atan2 of two coordinates).
        follower, leader: (k,) coefficients of each joint in x_f and in x_l (zero where it is not in it).
        polynomial: P's coefficients (c0, c1, ...).
    """

    coupling: Coupling
    q_index: np.ndarray
    v_index: np.ndarray
    unbounded: np.ndarray
    follower: np.ndarray
    leader: np.ndarray
    polynomial: np.ndarray


def coupling_row(model: pin.Model, coupling: Coupling) -> CouplingRow:
    """Resolve a coupling's joints on the model.

    Args:
        model: the Pinocchio model.
        coupling: the coupling declaration.

    Returns:
        The coupling's joint indices (configuration and velocity), continuity flags, follower and leader
        coefficients and polynomial.

    Raises:
        MalformedDescription: an unknown joint, a joint with more than one freedom, no follower.
    """
    where = f"coupling {coupling.name!r}"
    if not coupling.follower:
        raise MalformedDescription(where, "names no follower joint")
    terms = [(j, c, 0.0) for j, c in coupling.follower] + [(j, 0.0, c) for j, c in coupling.leader]
    q_index, v_index, unbounded, follower, leader = [], [], [], [], []
    for joint, f, lead in terms:
        if not model.existJointName(joint):
            raise MalformedDescription(where, f"joint {joint!r} not in the model")
        j = model.getJointId(joint)
        if model.nvs[j] != 1:
            raise MalformedDescription(
                where, f"joint {joint!r} has {model.nvs[j]} freedoms: a coupling joins one-freedom joints"
            )
        q_index.append(model.joints[j].idx_q)
        v_index.append(model.joints[j].idx_v)
        unbounded.append(model.nqs[j] == 2)
        follower.append(float(f))
        leader.append(float(lead))
    poly = np.asarray(coupling.polynomial, dtype=float)
    if poly.ndim != 1 or poly.size == 0 or not np.all(np.isfinite(poly)):
        raise MalformedDescription(where, f"polynomial {coupling.polynomial!r} is not a list of finite numbers")
    return CouplingRow(
        coupling,
        np.array(q_index, dtype=int),
        np.array(v_index, dtype=int),
        np.array(unbounded, dtype=bool),
        np.array(follower),
        np.array(leader),
        poly,
    )


def coupling_values(row: CouplingRow, q: np.ndarray) -> np.ndarray:
    """The values of a coupling's joints.

    Args:
        row: the coupling row.
        q: (..., nq) configurations.

    Returns:
        (..., k) the joints' values (rad or m; a continuous joint's is atan2 of its two coordinates).
    """
    x = q[..., row.q_index]
    if row.unbounded.any():
        angle = np.arctan2(q[..., row.q_index + 1], q[..., row.q_index])
        x = np.where(row.unbounded, angle, x)
    return x


def coupling_residual(rows: Sequence[CouplingRow], q: np.ndarray) -> np.ndarray:
    """Every coupling row's residual e = f . x - f_ref - P(l . x - l_ref).

    Args:
        rows: the coupling rows, in order (at least one).
        q: (..., nq) configurations.

    Returns:
        (..., len(rows)) residuals (rad or m).
    """
    out = []
    for row in rows:
        x = coupling_values(row, q)
        s = x @ row.leader - row.coupling.leader_ref
        out.append(x @ row.follower - row.coupling.follower_ref - np.polynomial.polynomial.polyval(s, row.polynomial))
    return np.stack(out, axis=-1)


def coupling_jacobian(rows: Sequence[CouplingRow], q: np.ndarray, nv: int) -> np.ndarray:
    """The coupling rows' Jacobian f - P'(s) l on their joints' velocity columns.

    Args:
        rows: the coupling rows, in order.
        q: (..., nq) configurations.
        nv: the model's velocity dimension.

    Returns:
        (..., len(rows), nv) the Jacobian (de/dt = J v).
    """
    out = np.zeros(q.shape[:-1] + (len(rows), nv))
    for k, row in enumerate(rows):
        s = coupling_values(row, q) @ row.leader - row.coupling.leader_ref
        slope = np.polynomial.polynomial.polyval(s, np.polynomial.polynomial.polyder(row.polynomial))
        for col, f, lead in zip(row.v_index, row.follower, row.leader):
            out[..., k, col] += f - slope * lead
    return out


def coupling_drift(rows: Sequence[CouplingRow], q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The coupling rows' drift gamma = -P''(s) (l . v)^2, with d2e/dt2 = J a + gamma.

    Args:
        rows: the coupling rows, in order (at least one).
        q: (..., nq) configurations.
        v: (..., nv) velocities.

    Returns:
        (..., len(rows)) the drift.
    """
    out = []
    for row in rows:
        s = coupling_values(row, q) @ row.leader - row.coupling.leader_ref
        curvature = np.polynomial.polynomial.polyval(s, np.polynomial.polynomial.polyder(row.polynomial, 2))
        out.append(-curvature * (v[..., row.v_index] @ row.leader) ** 2)
    return np.stack(out, axis=-1)
