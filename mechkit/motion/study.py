"""A motion study: assemble along an input law sample by sample, each continued from the previous one
(its branch kept), then velocities, accelerations, the efforts of the driven joints and every joint's
reaction for all samples at once.

Sample i is continued from the last assembled sample (`PathKinematics.assemble`); its warm start is the
law's guess (a scene's pose) when it has one, else the polynomial through the last `PREDICTOR_POINTS`
assembled configurations extrapolated to t_i (in the tangent space of the latest, `pin.difference` /
`pin.integrate`); the first sample is the mechanism's assembly continued from its home. On a smooth law
the warm start leaves one Newton step (measured in docs/motion.md, "Speed").
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from mechkit import core
from mechkit.base.exceptions import InvalidParameters, MechkitError
from mechkit.history.result import MotionResult, coordinate_names
from mechkit.mechanism import Mechanism
from mechkit.motion.inputs import InputLaw
from mechkit.motion.path import PathKinematics

Progress = Callable[[int, int], None]
"""(steps done, steps in all) -> None: each sample's kinematics is a step, the dynamics of all samples
the last N steps."""

Loads = Callable[[Mechanism, np.ndarray, float], Sequence]
"""(mechanism, q, t) -> Pinocchio external forces per joint (local frames), e.g. a thrust."""


def driven_model(mech: Mechanism, names: Sequence[str]) -> core.ClosureModel:
    """The closure model with a generalised force on every actuated joint and every input of the law
    (a passive input's force is what its spring or damper must supply); the file's tendon actuators kept.

    Args:
        mech: the mechanism.
        names: the law's driven joints.

    Returns:
        The closure model so driven.
    """
    driven = tuple(mech.actuated) + tuple(n for n in names if n not in mech.actuated)
    return mech.closure_model.with_actuation(driven, mech.closure_model.actuators)


def inverse_batch(
    mech: Mechanism,
    cm: core.ClosureModel,
    cd: core.ClosureData,
    q: np.ndarray,
    v: np.ndarray,
    a: np.ndarray,
    fexts: Sequence | None,
    determinacy: bool,
) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """Efforts, reactions and determinacy flags of N samples of `mech` driven as `cm` says, with the
    mechanism's joint springs.

    Args:
        mech: the mechanism.
        cm: its closure model, driven (`driven_model`).
        cd: a data of it.
        q: configurations (N, nq).
        v: velocities (N, nv).
        a: accelerations (N, nv).
        fexts: per-sample external forces (as `Mechanism.inverse_dynamics` takes them), or None.
        determinacy: flag the components static equilibrium fixes.

    Returns:
        (efforts (N, n_driven), N m or N; reactions (N, n_joints, 6), world [f, m] at each joint point;
            determinacy flags (N, n_joints, 6) or None).

    Raises:
        SingularConfiguration: a sample's drives cannot hold its motion.
    """
    out = core.inverse_dynamics_batch(cm, cd, q, v, a, fexts, mech.passive_forces(q, v), determinacy_test=determinacy)
    return out.efforts, out.reactions, out.determinate


#: How the reactions statics leaves open are fixed: by convention, or by the links' elasticity.
REACTIONS = ("rigid", "compliant")
#: Samples assembled between two batched singularity judgements (a singular sample re-assembles at most
#: this many samples after it, predicted from it).
JUDGED_BLOCK = 32
#: Assembled samples the warm start extrapolates from (a polynomial of degree one less).
PREDICTOR_POINTS = 3


def kinematics_along(
    path: PathKinematics,
    law: InputLaw,
    tol: float = 1e-12,
    skip_failures: bool = False,
    progress: Progress | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, list]:
    """The kinematics of every sample of a law.

    The closure is solved sample by sample from the warm start, blocks of `JUDGED_BLOCK` samples are
    judged for singularity at once (a singular sample fails as if judged alone: the samples after it
    are solved again from the good ones before it), then v, a and the axes are batched.

    Args:
        path: the path's kinematics (inputs and split fixed once).
        law: the input law.
        tol: closure residual of each assembly.
        skip_failures: a failing sample becomes a row of NaN and a listed failure instead of an error.
        progress: called after each sample with (done, total).

    Returns:
        (q (N, nq), v (N, nv), a (N, nv), world joint axes (N, n_joints, 3), the failures [(t (s), message)]).

    Raises:
        ClosureNotConverged, SingularConfiguration: as `study` (unless `skip_failures`).
    """
    model, n = path.model, len(law.t)
    q = np.full((n, model.nq), np.nan)
    kernel = path.closure_model.kernel
    J = np.full((n, kernel.size, model.nv), np.nan)
    Jw = np.full((n, 6, model.nv), np.nan)
    G = np.full((n, len(kernel.joints), 4, 4), np.nan)
    failures: list[tuple[float, str]] = []
    done: list[int] = []  # the samples assembled so far, in order: the predictor's points

    def fail(i: int, err: MechkitError) -> None:
        if not skip_failures:
            raise err
        failures.append((float(law.t[i]), str(err)))
        q[i] = np.nan

    i = 0
    while i < n:
        block, error = [], None
        while i < n and len(block) < JUDGED_BLOCK:
            try:
                if not done:
                    q[i] = path.first_guess(law.values[i], None if law.guesses is None else law.guesses[i])
                else:
                    last = done[: -PREDICTOR_POINTS - 1 : -1]
                    guess = law.guesses[i] if law.guesses is not None else path.predict(q[last], law.t[last], law.t[i])
                    q[i] = path.assemble(q[done[-1]], guess, law.values[i], tol)
            except MechkitError as err:
                error = (i, err)
                break
            block.append(i)
            done.append(i)
            i += 1
        if block:
            J[block], Jw[block], G[block] = path.jacobians(q[block])
        singular = path.singular(J[block]) if block else None
        if singular is not None:
            k, err = singular
            q[block[k + 1 :]] = np.nan
            del done[len(done) - len(block) + k :]
            fail(block[k], err)
            i = block[k] + 1
        elif error is not None:
            fail(*error)
            i = error[0] + 1
        if progress is not None:
            progress(i, 2 * n)
    good = np.flatnonzero(np.isfinite(q).all(axis=1))
    v = np.full((n, model.nv), np.nan)
    a = np.full((n, model.nv), np.nan)
    axes = np.full((n, len(path.axes.column) + len(path.axes.cut_joint), 3), np.nan)
    if good.size:
        v[good], a[good], axes[good] = path.motion(
            q[good], J[good], Jw[good], G[good], law.rates[good], law.accelerations[good]
        )
    return q, v, a, axes, failures


def study(
    mech: Mechanism,
    law: InputLaw,
    *,
    determinacy: bool = False,
    loads: Loads | None = None,
    progress: Progress | None = None,
    tol: float = 1e-12,
    skip_failures: bool = False,
    reactions: str = "rigid",
) -> MotionResult:
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
        reactions: "rigid" (the components statics leaves open by the minimum-norm convention) or
            "compliant" (every component fixed by the links' elasticity, `mechkit.elastic`; the flags
            then say which compatibility fixes).

    Returns:
        The motion: per sample q, v, a, efforts, every joint's reaction (world [f, m] at the joint point), axes
            and supports, with the failures skipped.

    Raises:
        ClosureNotConverged: a sample does not assemble near its warm start (the message says which).
        SingularConfiguration: the inputs do not determine the motion, or the drives cannot hold it.
        InvalidParameters: `reactions` neither "rigid" nor "compliant".
    """
    if reactions not in REACTIONS:
        raise InvalidParameters("reactions", reactions, f"one of {REACTIONS}")
    model, names, n = mech.model, list(law.names), len(law.t)
    driven = driven_model(mech, names)
    driven_data = driven.create_data()
    nj = len(driven.joint_names)
    q, v, a, axes, failures = kinematics_along(PathKinematics(mech, names), law, tol, skip_failures, progress)
    good = np.flatnonzero(np.isfinite(q).all(axis=1))
    fexts = None if loads is None else [loads(mech, q[i], float(law.t[i])) for i in good]
    efforts = np.full((n, len(driven.actuated)), np.nan)
    wrenches = np.full((n, nj, 6), np.nan)
    flags = np.zeros((n, nj, 6), dtype=bool) if determinacy else None
    try:  # all samples at once; where that fails and failures may be skipped, sample by sample
        batches = [good]
        out = [inverse_batch(mech, driven, driven_data, q[good], v[good], a[good], fexts, determinacy)]
    except MechkitError:
        if not skip_failures:
            raise
        batches, out = [], []
        for k, i in enumerate(good):
            one = None if fexts is None else [fexts[k]]
            try:
                out.append(
                    inverse_batch(mech, driven, driven_data, q[i : i + 1], v[i : i + 1], a[i : i + 1], one, determinacy)
                )
                batches.append(np.array([i]))
            except MechkitError as err:
                failures.append((float(law.t[i]), str(err)))
                q[i] = v[i] = a[i] = axes[i] = np.nan
    for rows, (u, w, f) in zip(batches, out):
        efforts[rows], wrenches[rows] = u, w
        if flags is not None:
            flags[rows] = f
    done = np.concatenate(batches) if batches else np.zeros(0, dtype=int)
    if reactions == "compliant" and done.size:
        from mechkit.elastic.elastic_model import ElasticModel

        compliant = ElasticModel(mech).compatible(q[done], efforts[done], wrenches[done], driven.actuated)
        efforts[done], wrenches[done] = compliant.efforts, compliant.reactions
        if flags is not None:
            flags[done] = compliant.determinate
    if progress is not None:
        progress(2 * n, 2 * n)
    return MotionResult(
        mech.spec.name,
        law.source,
        law.t.copy(),
        coordinate_names(model),
        q,
        v,
        a,
        driven.actuated,
        tuple(mech.actuated),
        efforts,
        driven.joint_names,
        np.array(driven.supports, dtype=bool),
        wrenches,
        axes,
        flags,
        tuple(sorted(failures)),
    )
