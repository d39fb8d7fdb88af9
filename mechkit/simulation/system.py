"""The equations of motion a simulation integrates: the core's constrained forward dynamics under the
force elements, with computed-torque drives and the fixed point of joint friction and reactions.

At a state (t, q, v):

1. every force element's load (`mechkit.forces`): generalised forces and body wrenches, summed into
   tau (the wrenches as J^T f);
2. the core's forward dynamics a0 = FD(q, v, tau) (`mechkit.core.forward_dynamics`, "proximal" by
   default); with driven joints D (prescribed inputs, held joints), FD is affine in tau, so the columns
   P_k = FD(tau + e_k) - a0 (k in D) give the efforts u that realise the law's accelerations:
   P_DD u = a_law - a0_D, a = a0 + P u (computed-torque motors);
3. with friction from the reactions: steps 1-2 under the friction of the previous evaluation's
   reactions at this state's axes and rates (lagged reactions: the integrator's stages are close),
   every joint's reaction at (q, v, a): from the proximal solve's multipliers and one RNEA pass
   (`simulation.anchor_reactions`), or with "kkt" by the core's inverse dynamics (the drives as
   actuators), the friction loads from them, and steps 1-2 once more under that friction
   (corrected): scheme "corrected", two forward solves and one reaction pass per evaluation.
   Its friction is one fixed-point iteration from the lagged one: its error against the converged fixed
   point is the iteration's contraction (the friction's sensitivity to its own reactions, mu r times the
   reactions' lever, about 1e-3 for pins of 5 mm) times the correction, which is itself held below
   `LAG_TOL` of the largest friction torque (where it is larger, at the start, after an event or where
   friction locks, the iteration goes on until it is that small). Measured on the four-bar released with
   friction at every pin (mu 0.2, r 10 mm) over 1 s: see tests/simulation/test_system.py and
   docs/simulation.md. Scheme "fixed point" iterates until the friction changes by less than
   `FRICTION_TOL` (relative), an Anderson(1) step between rounds (`_anderson`), `FrictionLocks` where it
   does not settle (both schemes).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from mechkit import core
from mechkit.base.exceptions import InvalidParameters, SingularConfiguration
from mechkit.forces import ForceElement, ForceState, FrictionLocks, generalized_of_wrenches
from mechkit.simulation import crossing
from mechkit.simulation.anchor_reactions import AnchorReactions, applies
from mechkit.simulation.prescribed import Drives

#: The friction fixed point stops when no friction torque changes by more than this, relative to the
#: largest (ours: far below the integrator's tolerances).
FRICTION_TOL = 1e-11
#: Iterations allowed to the friction fixed point before `FrictionLocks`.
FRICTION_ITERATIONS = 60
#: How friction from the reactions is found in an evaluation (see the module docstring).
FRICTION_SCHEMES = ("corrected", "fixed point")
#: Largest change of the friction by its correction, relative to the largest friction torque, that ends the
#: "corrected" scheme (ours: a larger one, at the start, after an event or where friction locks, goes on
#: iterating as the fixed point does until a change is this small, then corrects once more).
LAG_TOL = 1e-3


@dataclass
class Evaluation:
    """The equations of motion at one state.

    Attributes:
        a: (nv,) accelerations.
        efforts: (k,) efforts of the driven joints (`Drives.all` order; N m or N).
        generalized: (nv,) the force elements' generalised forces (N m or N), wrenches not included.
        wrenches: (njoints, 6) their body wrenches (`fext` convention).
        powers: (n_elements,) each element's non-conservative power (W).
        reactions: (n_joints, 6) every joint's reaction when friction needed it, else None.
        iterations: friction fixed-point iterations (0 without friction).
    """

    a: np.ndarray
    efforts: np.ndarray
    generalized: np.ndarray
    wrenches: np.ndarray
    powers: np.ndarray
    reactions: np.ndarray | None = None
    iterations: int = 0


def _anderson(x: tuple, g: tuple, last: tuple | None) -> tuple[tuple, tuple]:
    """One Anderson(1) step of the friction's fixed point x = g(x) (ours: it keeps the fixed point; measured
    on the ten-bar's deployment: fewer rounds per evaluation, see docs/simulation.md): from the round's
    x (tau, fext) and g(x), and the last round's residual and g, the next x, g - gamma (g - g_last) with
    gamma minimising the residuals' combination; g itself on the first round or where that is undefined.

    Returns:
        (the next (tau, fext), this round's (residual, g) flat, for the next step).
    """
    flat_x = np.concatenate([x[0], x[1].ravel()])
    flat_g = np.concatenate([g[0], g[1].ravel()])
    residual = flat_g - flat_x
    nxt = flat_g
    if last is not None:
        dr = residual - last[0]
        den = float(dr @ dr)
        if den > 0.0:
            gamma = float(residual @ dr) / den
            if math.isfinite(gamma):
                nxt = flat_g - gamma * (flat_g - last[1])
    n = len(x[0])
    return (nxt[:n], nxt[n:].reshape(x[1].shape)), (residual, flat_g)


class MechanismSystem:
    """A mechanism's equations of motion under force elements and drives.

    Args:
        mech (Mechanism): the mechanism (`mechkit.Mechanism`).
        elements: the force elements (its springs among them where wanted: `Mechanism.springs`).
        drives: the driven joints.
        method: the core's forward-dynamics method ("proximal", "lcaba", "kkt", "nullspace"), or "branch"
            (`mechkit.simulation.crossing.forward`: states on the manifold, the simulation's near-singular mode).
        baumgarte: (Kp 1/s^2, Kd 1/s) closure stabilisation in the accelerations, or None.
        friction_scheme: friction from the reactions per evaluation: "corrected" (the previous evaluation's
            friction corrected once) or "fixed point" (iterated to `FRICTION_TOL`); see the module docstring.

    Raises:
        InvalidParameters: an unknown friction scheme.
    """

    def __init__(
        self,
        mech,
        elements: list[ForceElement],
        drives: Drives,
        method: str = "proximal",
        baumgarte: tuple[float, float] | None = None,
        friction_scheme: str = "fixed point",
    ):
        self.mech, self.elements, self.method = mech, list(elements), method
        self.cm = mech.closure_model
        self.cd = self.cm.create_data()
        self.model = self.cm.model
        self.data = self.model.createData()
        self.settings = {} if method in ("lcaba",) else {"baumgarte": baumgarte or (0.0, 0.0)}
        self.friction = [k for k, e in enumerate(self.elements) if e.needs_reactions]
        self.plain = [k for k in range(len(self.elements)) if k not in self.friction]
        if friction_scheme not in FRICTION_SCHEMES:
            raise InvalidParameters(
                "friction_scheme", friction_scheme, f"expected one of {', '.join(FRICTION_SCHEMES)}"
            )
        self.scheme = friction_scheme
        nv = self.model.nv  # buffers held across evaluations (read-only: shared by the evaluations without elements)
        self._zero_tau, self._zero_fext = np.zeros(nv), np.zeros((self.model.njoints, 6))
        self._no_powers, self._no_efforts, self._unit = np.zeros(0), np.zeros(0), np.eye(nv)
        for buffer in (self._zero_tau, self._zero_fext, self._no_powers, self._no_efforts, self._unit):
            buffer.setflags(write=False)
        self._driven: dict[tuple[str, ...], tuple[core.ClosureModel, core.ClosureData]] = {}
        self._friction_start: np.ndarray | None = None  # the last evaluation's reactions
        # friction's reactions from the proximal solve's multipliers (`simulation.anchor_reactions`)
        self._by_anchors = method == "proximal" and bool(self.friction) and applies(self.cm)
        self._anchors = None
        self.drives = drives

    @property
    def drives(self) -> Drives:
        """The driven joints (setting them, e.g. when a latch catches, changes the equations)."""
        return self._drives

    @drives.setter
    def drives(self, drives: Drives) -> None:
        """Set the driven joints (their velocity indices follow).

        Args:
            drives: the new driven joints.
        """
        self._drives = drives
        self.drive_v = np.array([self.mech.v_index(j) for j in drives.all], dtype=int)

    def driven(self) -> tuple[core.ClosureModel, core.ClosureData]:
        """The closure model with the driven joints as actuators (for inverse dynamics), and a data."""
        names = self._drives.all
        if names not in self._driven:
            cm = self.cm.with_actuation(names)
            self._driven[names] = (cm, cm.create_data())
        return self._driven[names]

    def _fd(self, q: np.ndarray, v: np.ndarray, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
        """Accelerations under tau, and Pinocchio's anchor multipliers (a copy) where friction reads the
        reactions from them ("proximal"), else None."""
        if self.method == "branch":  # crossing: states on the manifold near a singular position (simulation.crossing)
            return crossing.forward(self.cm, self.cd, q, v, tau), None
        a = core.forward_dynamics(self.cm, self.cd, q, v, tau, self.method, **self.settings).a
        if not self._by_anchors:
            return a, None
        if self._anchors is None:  # the anchors exist after the first proximal call
            self._anchors = AnchorReactions(self.cm, self.cd.legacy["proximal"])
        return a, self._anchors.legacy.data.lambda_c.copy()

    def _loads(self, state: ForceState, which) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Sum of the generalised forces (nv,) and wrenches (njoints, 6) of elements `which`, and their powers."""
        tau = np.zeros(self.model.nv)
        fext = np.zeros((self.model.njoints, 6))
        powers = np.zeros(len(which))
        for i, k in enumerate(which):
            load = self.elements[k].load(state)
            if load.generalized is not None:
                tau += load.generalized
            if load.wrenches is not None:
                fext += load.wrenches
            powers[i] = load.power
        return tau, fext, powers

    def reactions(
        self, q: np.ndarray, v: np.ndarray, a: np.ndarray, generalized: np.ndarray, wrenches: np.ndarray
    ) -> core.InverseDynamicsResult:
        """The core's inverse dynamics with the drives as actuators (no determinacy test).

        Args:
            q: (nq,) configuration.
            v: (nv,) velocities.
            a: (nv,) accelerations.
            generalized: (nv,) the elements' generalised forces (N m or N), passive forces.
            wrenches: (njoints, 6) their body wrenches (`fext` convention), external forces.

        Returns:
            The core's result: the driven joints' efforts and every joint's reaction.
        """
        cm, cd = self.driven()
        fext = pin.StdVec_Force()
        for row in wrenches:
            fext.append(pin.Force(row[:3].copy(), row[3:].copy()))
        return core.inverse_dynamics(cm, cd, q, v, a, fext, generalized, determinacy_test=False)

    def _accelerations(
        self, q: np.ndarray, v: np.ndarray, tau: np.ndarray, acc: np.ndarray, P: tuple | None
    ) -> tuple[np.ndarray, np.ndarray, tuple | None, np.ndarray | None]:
        """Accelerations, drive efforts and anchor multipliers (or None) under tau; the drive columns P of the
        accelerations and of the multipliers are computed once per state (both affine in tau)."""
        a0, lam0 = self._fd(q, v, tau)
        if not self.drive_v.size:
            return a0, self._no_efforts, None, lam0
        if P is None:
            columns = [self._fd(q, v, tau + self._unit[k]) for k in self.drive_v]
            P = (
                np.column_stack([a - a0 for a, _ in columns]),
                None if lam0 is None else np.column_stack([lam - lam0 for _, lam in columns]),
            )
        try:
            u = np.linalg.solve(P[0][self.drive_v], acc - a0[self.drive_v])
        except np.linalg.LinAlgError:  # the drives' response block: a freedom lost, or drives that conflict
            raise SingularConfiguration(
                float("inf"), f"the drives {list(self._drives.all)} do not determine the accelerations here"
            ) from None
        return a0 + P[0] @ u, u, P, None if lam0 is None else lam0 + P[1] @ u

    def evaluate(self, t: float, q: np.ndarray, v: np.ndarray) -> Evaluation:
        """The equations of motion at a state.

        Args:
            t: the time (s).
            q: (nq,) configuration.
            v: (nv,) velocities.

        Returns:
            The `Evaluation`: accelerations, drive efforts, element loads and powers (and the reactions
            where friction needed them).

        Raises:
            FrictionLocks: the friction fixed point does not converge.
            SingularConfiguration: the drives cannot hold their law (a singular P_DD).
        """
        acc = self._drives.at(t)[2] if self.drive_v.size else None
        if not self.elements:
            a, u, _, _ = self._accelerations(q, v, self._zero_tau, acc, None)
            return Evaluation(a, u, self._zero_tau, self._zero_fext, self._no_powers)
        state = ForceState.at(self.model, self.data, q, v, t)
        tau_p, fext_p, pow_p = self._loads(state, self.plain)
        if not self.friction:
            tau = tau_p + generalized_of_wrenches(self.model, state.data, fext_p) if fext_p.any() else tau_p
            a, u, _, _ = self._accelerations(q, v, tau, acc, None)
            return Evaluation(a, u, tau_p, fext_p, pow_p)
        tau_f, fext_f = np.zeros_like(tau_p), np.zeros_like(fext_p)
        if self._friction_start is not None:  # the last evaluation's reactions, at this state's axes and rates
            state.reactions = self._friction_start
            tau_f, fext_f, _ = self._loads(state, self.friction)
        P, placed = None, False
        iterations, reactions, change, scale, last = 0, None, np.inf, 1.0, None
        while True:
            generalized, wrenches = tau_p + tau_f, fext_p + fext_f
            if self._anchors is None:
                tau = generalized + generalized_of_wrenches(self.model, state.data, wrenches)
            else:  # two Pinocchio passes instead of a Jacobian per body
                tau = generalized + self._anchors.generalized(q, wrenches)
            a, u, P, lam = self._accelerations(q, v, tau, acc, P)
            if iterations and self.scheme == "corrected" and change <= LAG_TOL * scale:
                break  # the lagged friction corrected once: a from the friction of its own reactions
            if lam is None:
                reactions = self.reactions(q, v, a, generalized, wrenches).reaction_values
            else:  # from the forward solve's own multipliers: one RNEA pass
                if not placed:  # the multipliers' map at this q, once per evaluation
                    self._anchors.at(state.data)
                    placed = True
                reactions = self._anchors(q, v, a, lam, wrenches)
            state.reactions = reactions
            new_tau, new_fext, pow_f = self._loads(state, self.friction)
            change = max(
                float(np.max(np.abs(new_tau - tau_f), initial=0.0)),
                float(np.max(np.abs(new_fext - fext_f), initial=0.0)),
            )
            scale = max(
                float(np.max(np.abs(new_tau), initial=0.0)), float(np.max(np.abs(new_fext), initial=0.0)), 1e-300
            )
            if self.scheme == "fixed point" and not (change <= FRICTION_TOL * scale or change == 0.0):
                (new_tau, new_fext), last = _anderson((tau_f, fext_f), (new_tau, new_fext), last)
            tau_f, fext_f = new_tau, new_fext
            iterations += 1
            if self.scheme == "fixed point" and (change <= FRICTION_TOL * scale or change == 0.0):
                break
            if iterations >= FRICTION_ITERATIONS:
                self._friction_start = None
                raise FrictionLocks(change, FRICTION_TOL * scale, iterations, f"t = {t:.6g} s")
            if self.scheme == "corrected" and change <= FRICTION_TOL * scale:
                break  # converged before the correction: a is already the fixed point's
        self._friction_start = reactions
        powers = np.empty(len(self.elements))
        powers[self.plain] = pow_p
        powers[self.friction] = pow_f
        return Evaluation(a, u, tau_p + tau_f, fext_p + fext_f, powers, reactions, iterations)

    def kinetic(self, q: np.ndarray, v: np.ndarray) -> float:
        """The kinetic energy.

        Args:
            q: (nq,) configuration.
            v: (nv,) velocities.

        Returns:
            The kinetic energy (J).
        """
        return float(pin.computeKineticEnergy(self.model, self.data, q, v))

    def potentials(self, q: np.ndarray) -> np.ndarray:
        """The potential energies.

        Args:
            q: (nq,) configuration.

        Returns:
            (1 + n_elements,) the model's gravity potential, then each element's potential (J).
        """
        gravity = float(pin.computePotentialEnergy(self.model, self.data, q))  # also places the joints
        return np.array([gravity] + [e.energy(self.model, self.data, q) for e in self.elements])
