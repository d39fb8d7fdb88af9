"""A motion study: assemble along an input law with warm starts, then velocities, accelerations, the
efforts of the driven joints and every joint's reaction, sample by sample.

Warm start of sample i: the law's guess (a scene's pose) when it has one, else the previous
configuration advanced by v dt + a dt^2 / 2 (`pin.integrate`), which keeps the assembly branch and
lets the closure solve converge in one or two Newton steps.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
import pinocchio as pin

from mechkit import dynamics
from mechkit.exceptions import MechkitError
from mechkit.mechanism import Mechanism
from mechkit.motion.inputs import InputLaw
from mechkit.motion.result import MotionResult

Progress = Callable[[int, int], None]
"""(samples done, samples in all) -> None, called after each sample."""

Loads = Callable[[Mechanism, np.ndarray, float], Sequence]
"""(mechanism, q, t) -> Pinocchio external forces per joint (local frames), e.g. a thrust."""


def coordinate_names(model: pin.Model) -> tuple[str, ...]:
    """Names of the q coordinates: the joint's name, `name[k]` for a joint of several coordinates."""
    out = []
    for j in range(1, model.njoints):
        n = model.joints[j].nq
        out += [model.names[j]] if n == 1 else [f"{model.names[j]}[{k}]" for k in range(n)]
    return tuple(out)


class JointAxes:
    """Unit axes (world frame) of every joint of an inverse-dynamics problem.

    Tree joints of one degree of freedom: the rotation axis (revolute) or the sliding direction
    (prismatic), from the joint's motion subspace. Cut joints: the declared axis of a revolute or
    prismatic closure, in frame_a's frame. Other joints (spherical, Hooke, weld) have no single axis: NaN.
    """

    def __init__(self, mech: Mechanism, problem: dynamics.InverseDynamicsProblem):
        model = mech.model
        data = model.createData()
        pin.forwardKinematics(model, data, mech.home_q)
        self.tree = np.full((model.njoints, 3), np.nan)
        for j in range(1, model.njoints):
            if model.joints[j].nv == 1:
                S = np.asarray(data.joints[j].S).reshape(6)
                local = S[3:] if np.linalg.norm(S[3:]) > 0 else S[:3]
                self.tree[j] = local / np.linalg.norm(local)
        self.cuts = [(c.frame_a, np.asarray(c.closure.axis, dtype=float) if c.closure.kind in ("revolute", "prismatic")
                      else np.full(3, np.nan)) for c in problem.rows.cuts]

    def world(self, data: pin.Data) -> np.ndarray:
        """(n_joints, 3) world axes at the configuration `data` holds (joint and frame placements current)."""
        R = np.array([data.oMi[j].rotation for j in range(1, len(self.tree))]).reshape(-1, 3, 3)
        tree = np.einsum("jab,jb->ja", R, self.tree[1:])
        cuts = [data.oMf[f].rotation @ axis for f, axis in self.cuts]
        return np.vstack([tree, *cuts]) if cuts else tree


def driven_problem(mech: Mechanism, names: Sequence[str]) -> dynamics.InverseDynamicsProblem:
    """The inverse-dynamics problem with a generalised force on every actuated joint and every input
    of the law (a passive input's force is what its spring or damper must supply)."""
    driven = tuple(mech.actuated) + tuple(n for n in names if n not in mech.actuated)
    return dynamics.InverseDynamicsProblem(
        mech.model, mech.model.createData(), mech.rows, mech.full_rows,
        np.array([mech.v_index(j) for j in driven], dtype=int), driven)


def study(mech: Mechanism, law: InputLaw, *, determinacy: bool = False, loads: Loads | None = None,
          progress: Progress | None = None, tol: float = 1e-12, skip_failures: bool = False) -> MotionResult:
    """Efforts and every joint's reaction along an input law.

    Args:
        mech: the mechanism.
        law: the driven joints' values, rates and accelerations over time (`mechkit.motion.inputs`).
        determinacy: also flag the reaction components static equilibrium fixes (one SVD per sample).
        loads: optional external forces as a function of (mechanism, q, t).
        progress: called after each sample with (done, total).
        tol: closure residual of each assembly (m for position rows).
        skip_failures: a sample that does not assemble or is singular (a motion law starting at a
            singularity) becomes a row of NaN, listed in `MotionResult.failures`, instead of an error.

    Raises:
        ClosureNotConverged: a sample does not assemble near its warm start (the message says which).
        SingularConfiguration: the inputs do not determine the motion, or the drives cannot hold it.
    """
    model, names, n = mech.model, list(law.names), len(law.t)
    problem = driven_problem(mech, names)
    axes = JointAxes(mech, problem)
    nj = len(problem.joint_names)
    q = np.empty((n, model.nq))
    v = np.empty((n, model.nv))
    a = np.empty((n, model.nv))
    efforts = np.empty((n, len(problem.actuated_names)))
    reactions = np.empty((n, nj, 6))
    world_axes = np.empty((n, nj, 3))
    flags = np.zeros((n, nj, 6), dtype=bool) if determinacy else None
    failures: list[tuple[float, str]] = []
    last = None  # the last sample that succeeded: the predictor's start
    for i in range(n):
        if law.guesses is not None:
            guess = law.guesses[i]
        elif last is not None:
            dt = law.t[i] - law.t[last]
            guess = pin.integrate(model, q[last], v[last] * dt + 0.5 * a[last] * dt * dt)
        else:
            guess = None
        try:
            q[i] = mech.assemble(dict(zip(names, law.values[i])), guess=guess, tol=tol)
            v[i] = mech.velocities(q[i], law.rates[i], inputs=names)
            a[i] = mech.accelerations(q[i], v[i], law.accelerations[i], inputs=names)
            fext = None if loads is None else loads(mech, q[i], float(law.t[i]))
            result = dynamics.inverse_dynamics(problem, q[i], v[i], a[i], fext, determinacy)
        except MechkitError as err:
            if not skip_failures:
                raise
            failures.append((float(law.t[i]), str(err)))
            for x in (q, v, a, efforts, reactions, world_axes):
                x[i] = np.nan
        else:
            efforts[i] = [result.efforts[j] for j in problem.actuated_names]
            reactions[i] = [result.reactions[j].wrench for j in problem.joint_names]
            world_axes[i] = axes.world(problem.data)
            if flags is not None:
                flags[i] = [result.reactions[j].determinate for j in problem.joint_names]
            last = i
        if progress is not None:
            progress(i + 1, n)
    return MotionResult(mech.spec.name, law.source, law.t.copy(), coordinate_names(model), q, v, a,
                        problem.actuated_names, tuple(mech.actuated), efforts, problem.joint_names,
                        np.array(problem.supports, dtype=bool), reactions, world_axes, flags, tuple(failures))
