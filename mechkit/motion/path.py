"""Kinematics along a path: per sample, the closure solve continued from the previous sample (the one
sequential step: `mechkit.core.continue_from`, so the path keeps its assembly branch), then velocities,
accelerations and the joint axes of all samples at once.

The core's functions (`assemble`, `kinematic_pass`, `passive_verdict`, `solve_passive`), called with
what a path fixes once: the split of given and solved coordinates is the same for every sample, the
placements and Jacobians gathered for the singularity judgement serve the velocities, and the
judgement, velocities, accelerations and axes are batched over many samples.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pinocchio as pin

from mechkit import core
from mechkit.base.exceptions import ClosureNotConverged, SingularConfiguration
from mechkit.history.axes import JointAxes
from mechkit.mechanism import Mechanism


class PathKinematics:
    """The kinematics of one mechanism along a path of given input coordinates.

    Args:
        mech: the mechanism.
        names: the given (driven) joints.
    """

    def __init__(self, mech: Mechanism, names: Sequence[str]):
        self.mech, self.model = mech, mech.model
        self.closure_model, self.closure_data = mech.closure_model, mech.closure_model.create_data()
        self.split = mech.closure_model.split(tuple(names))
        self.input_q = np.array([mech.q_index(j) for j in names], dtype=int)
        self.names = tuple(names)
        self.axes = JointAxes(mech)

    def first_guess(self, values: np.ndarray, guess: np.ndarray | None = None) -> np.ndarray:
        """The assembly at the first sample: continued from the law's pose when it is closed, else from
        the mechanism's home (`Mechanism.assembly`).

        Args:
            values: the inputs' values at the first sample (k,), rad or m.
            guess: the law's pose at the first sample (nq,), or None.

        Returns:
            The assembled configuration (nq,).
        """
        return self.mech.assemble(dict(zip(self.names, values)), guess)

    def predict(self, q: np.ndarray, t: np.ndarray, t_next: float) -> np.ndarray:
        """Warm start at time t_next from the last assembled samples q (k, nq) at times t (k,), latest
        first: the polynomial through them (degree k - 1, Lagrange, in the tangent space at q[0]).

        Args:
            q: the last assembled samples (k, nq), latest first.
            t: their times (k,), s.
            t_next: the next sample's time, s.

        Returns:
            The warm start (nq,).
        """
        x = np.zeros(self.model.nv)
        for j in range(1, len(t)):
            weight = 1.0
            for m in range(len(t)):
                if m != j:
                    weight *= (t_next - t[m]) / (t[j] - t[m])
            x += weight * pin.difference(self.model, q[0], q[j])
        return pin.integrate(self.model, q[0], x)

    def assemble(self, previous: np.ndarray, guess: np.ndarray, values: np.ndarray, tol: float) -> np.ndarray:
        """q of one sample on the previous sample's branch: continued from it (`core.continue_from`, steps
        of at most `core.continuation.MAX_STEP` in the inputs), the solve starting from `guess` where one
        step suffices (its singularity is judged by `singular`).

        Args:
            previous: the previous sample's configuration (nq,), closed.
            guess: a configuration near the sample (nq,): the warm start.
            values: the inputs' values (k,), rad or m.
            tol: the closure tolerance.

        Returns:
            The assembled configuration (nq,).

        Raises:
            ClosureNotConverged: the previous sample's branch cannot be followed to this one.
        """
        target = np.array(previous, dtype=float)
        target[self.input_q] = values
        out = core.continue_from(
            self.closure_model, self.closure_data, previous, target, self.split, tol=tol, start=guess
        )
        if out is None:
            residual = float(np.linalg.norm(core.closure_residual(self.closure_model, self.closure_data, target)))
            raise ClosureNotConverged(residual, tol, 0, "the previous sample's branch cannot be followed to this one")
        return out.q

    def jacobians(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Closure and joint Jacobians of N assembled samples.

        Args:
            q: the configurations (N, nq).

        Returns:
            (closure Jacobians (N, rows, nv), world joint Jacobians (N, 6, nv), the rows' used joint placements
                (N, n_used, 4, 4)).
        """
        G, Jw, _ = core.kinematic_pass(self.closure_model, self.closure_data, q)
        return self.closure_model.kernel.evaluate(G, Jw, q)[1], Jw, G

    def singular(self, J: np.ndarray) -> tuple[int, SingularConfiguration] | None:
        """The first of N samples where the inputs do not determine the motion (`core.passive_verdict` at
        the closure tolerance).

        Args:
            J: the samples' closure Jacobians (N, rows, nv).

        Returns:
            (its index, the error saying why), or None when every sample is regular.
        """
        free_v = self.split.free_v
        s = np.linalg.svd(J[:, :, free_v], compute_uv=False)
        _, bad = core.passive_verdict(s, free_v.size, np.full(len(J), core.CLOSURE_TOL))
        if not bad.any():
            return None
        i = int(np.argmax(bad))
        return i, core.singular_error(s[i], free_v.size, core.CLOSURE_TOL)

    def motion(
        self, q: np.ndarray, J: np.ndarray, Jw: np.ndarray, G: np.ndarray, rates: np.ndarray, accelerations: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Velocities, accelerations and joint axes of N assembled samples, batched (judged regular
        already).

        Args:
            q: the configurations (N, nq).
            J: their closure Jacobians (N, rows, nv) (`jacobians`).
            Jw: their world joint Jacobians (N, 6, nv).
            G: the rows' used joint placements (N, n_used, 4, 4).
            rates: the inputs' rates (N, k), rad/s or m/s.
            accelerations: the inputs' accelerations (N, k), rad/s^2 or m/s^2.

        Returns:
            (v (N, nv), a (N, nv), world joint axes (N, n_joints, 3)).
        """
        cm, cd = self.closure_model, self.closure_data
        residual = np.full(len(q), core.CLOSURE_TOL)
        v, _ = core.solve_passive(cm, J, Jw, self.split, rates, None, residual, judged=True)
        G, Jw, dJ = core.kinematic_pass(cm, cd, q, v)
        k = cm.kernel
        gamma = k.drift(G, k.twists(Jw, v), k.twists(dJ, v), q, v)
        a, _ = core.solve_passive(cm, J, Jw, self.split, accelerations, gamma, residual, judged=True)
        return v, a, self.axes.world(Jw, G)
