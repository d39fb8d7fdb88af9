"""Joint friction from the reaction (Adams-like): a revolute pin rubs with a torque that grows with the
load it carries. Tree joints and loop-cut joints alike.

For a revolute joint of unit axis a carrying the reaction [f, m] (world, about the joint origin), the
load measure and the friction torque's size are (Adams' FRICTION statement, with its names):

    F_a = |f . a|                 axial force            (collar, Adams' friction arm R_n)
    F_r = |f - (f . a) a|         radial force           (pin radius R_p)
    M_b = |m - (m . a) a|         bending moment         (bending reaction arm R_b)
    T   = mu [ r (F_pre + F_r + M_b / b) + r_c F_a ]

with mu the friction coefficient, r the pin radius (m), b the bending arm (m; the pin's bearing
length: M_b / b is the edge force the moment adds; inf leaves bending out), r_c the collar radius
(m; 0 leaves the axial force out) and F_pre the preload (N, a radial force of assembly). The torque
on the child side is -T tanh(w / threshold), w the child's rate about a relative to the parent
(`mechkit.forces.coulomb`: the regularisation near zero speed); on a cut joint the child side is
frame_b's body and the parent frame_a's. For a planar mechanism modelled in space the axial force
and the bending moment are statically indeterminate (their values are a convention): leave b and
r_c out there.

The torque depends on the reactions, which depend on the torque: `FrictionState` iterations (in
`mechkit.simulation`) solve that fixed point; where it does not converge, friction locks the
mechanism (`FrictionLocks`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import astuple, dataclass

import numpy as np
import pinocchio as pin

from mechkit.base.exceptions import InvalidParameters, MechkitError
from mechkit.forces.coulomb import SPEED_THRESHOLD, smooth_sign
from mechkit.forces.element import ForceElement, ForceState, Load


class FrictionLocks(MechkitError):
    """The fixed point of reactions and friction does not converge: friction locks the mechanism (the
    friction a load calls for grows faster than the load), or holds it against every effort.

    Attributes:
        change: the last iteration's largest change of a friction torque (N m).
        tol: the tolerance it had to reach (N m).
        iterations: the iterations made.
    """

    def __init__(self, change: float, tol: float, iterations: int, what: str = ""):
        self.change, self.tol, self.iterations = change, tol, iterations
        super().__init__(
            f"joint friction locks the mechanism{': ' + what if what else ''} (the fixed point of "
            f"reactions and friction still changes by {change:.3g} N m > {tol:.3g} after {iterations} "
            "iterations)"
        )


@dataclass(frozen=True)
class PinFriction:
    """One revolute joint's friction data (see the module docstring).

    Attributes:
        mu: friction coefficient (>= 0).
        radius: pin radius r (m, > 0).
        bending_arm: b (m, > 0; inf: bending moment left out).
        collar_radius: r_c (m, >= 0; 0: axial force left out).
        preload: F_pre (N, >= 0).
        threshold: regularisation rate (rad/s, > 0).
    """

    mu: float
    radius: float
    bending_arm: float = math.inf
    collar_radius: float = 0.0
    preload: float = 0.0
    threshold: float = SPEED_THRESHOLD

    def __post_init__(self) -> None:
        """Refuse, by name, a value no pin can have (a negative coefficient, a pin of no radius, NaN)."""
        limits = {
            "mu": (self.mu, 0.0, False),
            "radius": (self.radius, 0.0, True),
            "bending_arm": (self.bending_arm, 0.0, True),
            "collar_radius": (self.collar_radius, 0.0, False),
            "preload": (self.preload, 0.0, False),
            "threshold": (self.threshold, 0.0, True),
        }
        for name, (value, low, strict) in limits.items():
            finite = math.isfinite(value) or (name == "bending_arm" and value == math.inf)
            if not finite or value < low or (strict and value == low):
                raise InvalidParameters(
                    f"friction {name}", value, f"must be {'>' if strict else '>='} {low:g} and finite"
                )

    def torque(self, wrench: np.ndarray, axis: np.ndarray) -> float:
        """The friction torque's size T for a reaction.

        Args:
            wrench: (6,) the joint's reaction [f (N), m (N m)], world axes, about the joint origin.
            axis: (3,) the joint's unit axis (world).

        Returns:
            T (N m, >= 0).
        """
        return float(sizes(np.array([astuple(self)[:5]]), wrench[None], axis[None])[0])


def sizes(specs: np.ndarray, wrenches: np.ndarray, axes: np.ndarray) -> np.ndarray:
    """The friction torques' sizes T of several pins at once (see the module docstring).

    Args:
        specs: (n, 5) each pin's (mu, radius, bending_arm, collar_radius, preload), as `PinFriction`.
        wrenches: (n, 6) their reactions [f (N), m (N m)], world axes, about the joint origins.
        axes: (n, 3) their unit axes (world).

    Returns:
        (n,) T (N m, >= 0).
    """
    f, m = wrenches[:, :3], wrenches[:, 3:]
    axial = np.einsum("ij,ij->i", f, axes)
    radial_f = f - axial[:, None] * axes
    bending_m = m - np.einsum("ij,ij->i", m, axes)[:, None] * axes
    radial = np.sqrt(np.einsum("ij,ij->i", radial_f, radial_f))
    bending = np.sqrt(np.einsum("ij,ij->i", bending_m, bending_m))
    mu, radius, arm, collar, preload = specs.T
    return mu * (radius * (preload + radial + bending / arm) + collar * np.abs(axial))  # bending / inf = 0


class ReactionFriction(ForceElement):
    """Friction torques from the reactions of revolute joints, tree joints and loop cuts.

    Args:
        model: the tree.
        joint_names: the reactions' joints (`ClosureModel.joint_names`: tree joints, then cut joints).
        cuts: the cuts' rows (`ClosureModel.kernel.cuts`, in closure order), for the cut joints' frames.
        joints: joint name -> `PinFriction`.
        name: the element's name.

    Raises:
        InvalidParameters: an unknown joint, a joint that is not revolute, data out of range.
    """

    role = "dissipative"
    friction = True
    needs_reactions = True

    def __init__(
        self,
        model: pin.Model,
        joint_names: Sequence[str],
        cuts: Sequence,
        joints: Mapping[str, PinFriction],
        name: str = "reaction friction",
    ):
        self.name, self.joints = name, dict(joints)
        n_tree = model.njoints - 1
        by_cut = {c.closure.name: c for c in cuts}
        self._tree, self._cuts = [], []  # (name, reaction index, spec, velocity index) / (name, index, spec, cut rows)
        for joint, spec in self.joints.items():
            if joint not in joint_names:
                raise InvalidParameters("friction", joint, f"no such joint; joints: {list(joint_names)}")
            k = list(joint_names).index(joint)
            if k < n_tree:
                jm = model.joints[k + 1]
                if jm.nv != 1 or not jm.shortname().startswith(("JointModelR", "JointModelRevolute")):
                    raise InvalidParameters("friction", joint, f"a {jm.shortname()} joint: revolute joints only")
                self._tree.append((joint, k, spec, jm.idx_v))
            else:
                cut = by_cut[joint]
                if cut.closure.kind != "revolute":
                    raise InvalidParameters("friction", joint, f"a {cut.closure.kind} cut: revolute joints only")
                self._cuts.append((joint, k, spec, cut))
        pins = self._tree + self._cuts  # one array per quantity, tree joints first, for `sizes`
        self._k = np.array([k for _, k, _, _ in pins], dtype=int)
        self._specs = np.array([astuple(spec)[:5] for _, _, spec, _ in pins]).reshape(-1, 5)
        self._rate = np.array([spec.threshold for _, _, spec, _ in pins])
        self._tree_v = np.array([iv for _, _, _, iv in self._tree], dtype=int)
        self._cut_bodies = [  # per cut: (body joint, sign of the torque on it), the ground left out
            [
                (model.frames[f].parentJoint, sign)
                for f, sign in ((cut.frame_b, 1.0), (cut.frame_a, -1.0))
                if model.frames[f].parentJoint
            ]
            for _, _, _, cut in self._cuts
        ]
        self._at: tuple | None = None  # (state, axes, rates, signs, cut moment map): one state's geometry

    def _geometry(self, state: ForceState) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The pins' world axes (n, 3), rates (n,) and regularised signs (n,), and the map (njoints, 3, n_cuts)
        from the cut joints' torques to their bodies' moments (`fext`): computed once per state object (its
        q and v do not change; its reactions do, round after round of the friction's fixed point)."""
        if self._at is not None and self._at[0] is state:
            return self._at[1:]
        model, data = state.model, state.data
        axes = np.empty((len(self._k), 3))
        rates = np.empty(len(self._k))
        n_tree = len(self._tree)
        axes[:n_tree] = data.J.reshape(6, -1)[3:, self._tree_v].T
        rates[:n_tree] = state.v[self._tree_v]
        moments = np.zeros((model.njoints, 3, len(self._cuts)))
        for i, (_, _, _, cut) in enumerate(self._cuts):
            axis = axes[n_tree + i] = data.oMf[cut.frame_a].rotation @ cut.closure.axis
            w_a = pin.getFrameVelocity(model, data, cut.frame_a, pin.LOCAL_WORLD_ALIGNED).angular
            w_b = pin.getFrameVelocity(model, data, cut.frame_b, pin.LOCAL_WORLD_ALIGNED).angular
            rates[n_tree + i] = (w_b - w_a) @ axis
            for joint, sign in self._cut_bodies[i]:
                moments[joint, :, i] += sign * (data.oMi[joint].rotation.T @ axis)
        self._at = (state, axes, rates, smooth_sign(rates, self._rate), moments)
        return self._at[1:]

    def load(self, state: ForceState) -> Load:
        """The friction torques at a state and their power.

        Args:
            state: the state, with its reactions (none yet: no torque).

        Returns:
            The `Load`: generalised forces (nv,) at the tree joints, body wrenches (njoints, 6) (`fext`
            convention) of the cut joints' torques, and their power (W, <= 0).
        """
        model = state.model
        tau = np.zeros(model.nv)
        wrenches = np.zeros((model.njoints, 6))
        if state.reactions is None:
            return Load(tau, wrenches, 0.0)
        axes, rates, signs, moments = self._geometry(state)
        torques = -sizes(self._specs, state.reactions[self._k], axes) * signs
        n_tree = len(self._tree)
        tau[self._tree_v] = torques[:n_tree]  # one freedom per joint: no index repeats
        if self._cuts:
            wrenches[:, 3:] = moments @ torques[n_tree:]
        return Load(tau, wrenches, float(torques @ rates))

    def torques(self, state: ForceState) -> dict[str, float]:
        """The friction torques' sizes at a state with reactions (no sign, no regularisation).

        Args:
            state: the state; its reactions must be set.

        Returns:
            Joint name -> T (N m, >= 0).
        """
        out = {
            name: spec.torque(state.reactions[k], state.data.J.reshape(6, -1)[3:, iv])
            for name, k, spec, iv in self._tree
        }
        out.update(
            {
                name: spec.torque(state.reactions[k], state.data.oMf[cut.frame_a].rotation @ cut.closure.axis)
                for name, k, spec, cut in self._cuts
            }
        )
        return out
