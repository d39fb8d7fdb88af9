"""Assembly: closing every loop from a start, with the given joints held.

`assemble` runs Gauss-Newton (or Levenberg-Marquardt) on the kernel's exact rows; from far away it
needs more. The kernel's alignment rows (u . w = 0, u fixed in frame_a, w in frame_b) are exact and
regular near a closed loop, but a frame turned half a turn satisfies them too (a weld's three dot
products vanish at a rotation of pi about an axis), so from a far start (a file's neutral pose)
Gauss-Newton on them can stall or close on the wrong side. The far phase (`from_far`) replaces each
cut's rotation rows by differences of axes fixed in both frames, which vanish only when the frames
agree: a revolute cut's axis, R_b n - R_a n (3 rows); a weld's or a prismatic cut's three axes,
R_b e_k - R_a e_k (9 rows; a planar weld's one in-plane axis); a Hooke cut keeps its one dot product
(its cross axes are never equal). Position rows and coupling rows are the kernel's. From the
configuration near closure it reaches, the exact rows' solve finishes; `flip` tells a closed loop
from a flipped one.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin
from scipy.linalg import lapack

from mechkit.base.exceptions import ClosureNotConverged
from mechkit.core import rank
from mechkit.core.kinematics import kinematic_pass
from mechkit.core.model import ClosureData, ClosureModel, InputSplit

#: Closure solvers of `assemble`.
ASSEMBLY_METHODS = ("newton", "lm")
#: Largest orientation disagreement of a cut's frames (the norm of its axis differences) of a closed loop.
FLIP_TOL = 1e-6
#: Largest iterations of the far phase, and its stopping residual (m and dimensionless, mixed; ours:
#: near enough for Newton on the exact rows).
FAR_ITERATIONS, FAR_TOL = 300, 1e-10
#: A start where the far residual is stationary (a linkage written flat, every loop collinear): its
#: gradient below this fraction of |J| |e| (ours). From there the far phase restarts from `RESTARTS`
#: deterministic (seeded) perturbations of the free coordinates, each of at most `RESTART_SIZE` (rad or
#: m; ours) per coordinate.
STATIONARY_TOL, RESTARTS, RESTART_SIZE = 1e-9, 4, 0.3


def _axes(cut) -> np.ndarray:
    """(k, 3) the unit vectors, in both frames' coordinates, whose world images must agree for the cut."""
    c = cut.closure
    if c.kind == "revolute" and cut.alignments:
        return np.asarray(c.axis, dtype=float)[None]
    if c.kind in ("weld", "prismatic") and cut.alignments:
        return np.eye(3) if len(cut.alignments) == 3 else np.asarray(cut.alignments[0][0], dtype=float)[None]
    return np.zeros((0, 3))


def _far_rows(cm: ClosureModel, cd: ClosureData, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
    """The flip-free residual (rows,), its Jacobian (rows, nv), and the norm of its axis-difference rows
    alone, at q (`computeJointJacobians` run here)."""
    model, kernel, data = cm.model, cm.kernel, cd.pin
    pin.computeJointJacobians(model, data, q)
    G = np.array([data.oMi[int(j)].homogeneous for j in kernel.joints]).reshape(-1, 4, 4)
    e, J, _ = kernel.evaluate(G, cd.J, q)
    keep = np.ones(kernel.size, dtype=bool)
    extra_e, extra_J = [], []
    support = {int(j): kernel.support[k] for k, j in enumerate(kernel.joints)}
    for cut, rows in zip(kernel.cuts, kernel.cut_slices):
        axes = _axes(cut)
        if not len(axes):
            continue
        keep[rows.start + cut.positions.shape[1] : rows.stop] = False  # its dot-product rows
        fa, fb = model.frames[cut.frame_a], model.frames[cut.frame_b]
        Ra = data.oMi[fa.parentJoint].rotation @ fa.placement.rotation
        Rb = data.oMi[fb.parentJoint].rotation @ fb.placement.rotation
        wa, wb = (cd.J[3:] * support[f.parentJoint] for f in (fa, fb))
        for axis in axes:
            ra, rb = Ra @ axis, Rb @ axis
            extra_e.append(rb - ra)
            extra_J.append(-pin.skew(rb) @ wb + pin.skew(ra) @ wa)
    if not extra_e:
        return e, J, 0.0
    axes = np.concatenate(extra_e)
    return np.concatenate([e[keep], axes]), np.vstack([J[keep], *extra_J]), float(np.linalg.norm(axes))


def flip(cm: ClosureModel, data: pin.Data) -> float:
    """How far the cuts' frames disagree in orientation at the joint placements `data.oMi` holds.

    Args:
        cm: the closure model whose cuts are checked.
        data: Pinocchio data whose `oMi` holds the joint placements (after `forwardKinematics`).

    Returns:
        The norm of the cuts' axis differences (R_b n - R_a n over their axes n): 0 at a closed loop,
        about 2 where the kernel's rows vanish with a frame turned half a turn.
    """
    model, total = cm.model, 0.0
    for cut in cm.kernel.cuts:
        axes = _axes(cut)
        if len(axes):
            fa, fb = model.frames[cut.frame_a], model.frames[cut.frame_b]
            Ra = data.oMi[fa.parentJoint].rotation @ fa.placement.rotation
            Rb = data.oMi[fb.parentJoint].rotation @ fb.placement.rotation
            total += float(np.sum(((Rb - Ra) @ axes.T) ** 2))
    return float(np.sqrt(total))


def from_far(cm: ClosureModel, cd: ClosureData, q0: np.ndarray, split: InputSplit) -> np.ndarray:
    """A configuration near closure from q0, moving only the coordinates of `split.free_v`.

    Levenberg-Marquardt with Nielsen's damping update on the flip-free residual (see the module). Uses
    `cd.pin` as workspace.

    Args:
        cm: the closure model.
        cd: its data (workspace).
        q0: (nq,) starting configuration.
        split: which joints are given; only the coordinates of `split.free_v` move.

    Returns:
        (nq,) the configuration reached (near closure, not necessarily closed to tolerance).
    """
    model, free = cm.model, split.free_v
    q = q0.copy()
    e, J, _ = _far_rows(cm, cd, q)
    cost = float(e @ e)
    mu, nu = 1e-3 * float(np.max(np.sum(J[:, free] ** 2, axis=0), initial=1.0)), 2.0
    for _ in range(FAR_ITERATIONS):
        if np.sqrt(cost) <= FAR_TOL:
            break
        Jf = J[:, free]
        g = Jf.T @ e
        try:
            step = -np.linalg.solve(Jf.T @ Jf + mu * np.eye(free.size), g)
        except np.linalg.LinAlgError:
            mu, nu = mu * nu, 2 * nu
            continue
        full = np.zeros(model.nv)
        full[free] = step
        trial = pin.integrate(model, q, full)
        e_trial, J_trial, _ = _far_rows(cm, cd, trial)
        trial_cost = float(e_trial @ e_trial)
        predicted = float(step @ (mu * step - g))
        if np.isfinite(trial_cost) and trial_cost < cost and predicted > 0:
            rho = (cost - trial_cost) / predicted
            q, e, J, cost = trial, e_trial, J_trial, trial_cost
            mu, nu = mu * max(1.0 / 3.0, 1.0 - (2.0 * rho - 1.0) ** 3), 2.0
        else:
            mu, nu = mu * nu, 2 * nu
        if mu > 1e16:
            break
    return q


@dataclass(frozen=True)
class Assembly:
    """A solved closure: configuration q (nq,), Newton steps taken, residual norm reached, the branch
    taken (how it was reached, naming its reference: "Newton from the keyframe 'home'", "continued from
    the home assembly"), and the revolute joints left outside their limits
    (`mechkit.core.continuation.wrap_into_limits`)."""

    q: np.ndarray
    iterations: int
    residual: float
    branch: str = "Newton from the start given"
    outside: tuple[str, ...] = ()


def _residual_and_jacobian(
    cm: ClosureModel, cd: ClosureData, q: np.ndarray, jacobian: bool
) -> tuple[np.ndarray, np.ndarray | None, float]:
    G, J, _ = kinematic_pass(cm, cd, q[None]) if jacobian else (_placements(cm, cd, q), None, None)
    if jacobian:
        e, Jc, _ = cm.kernel.evaluate(G[0], J[0], q)
    else:
        e, Jc = cm.kernel.residual(G[0], q), None
    return e, Jc, float(np.sqrt(e @ e))


def _placements(cm: ClosureModel, cd: ClosureData, q: np.ndarray) -> np.ndarray:
    """(1, n_used, 4, 4) placements of the used joints at q after `forwardKinematics` only (the data's buffer)."""
    pin.forwardKinematics(cm.model, cd.pin, q)
    return cd.used_placements()[None]


def _newton_step(J: np.ndarray, e: np.ndarray) -> np.ndarray:
    """Minimum-norm x with J x = -e: LAPACK gesv when J is square and regular, else lstsq."""
    if J.shape[0] == J.shape[1]:
        _, _, x, info = lapack.dgesv(J, e)
        if info == 0:
            return -x
    return -np.linalg.lstsq(J, e, rcond=None)[0]


def assemble(
    cm: ClosureModel,
    cd: ClosureData,
    q0: np.ndarray,
    split: InputSplit,
    *,
    tol: float = rank.CLOSURE_TOL,
    max_iter: int = 60,
    method: str = "newton",
    jacobian_at_trials: bool = True,
) -> Assembly:
    """Close every loop by moving the coordinates of `split.free_v`, keeping the given joints at q0's values.

    The exact rows' solve (`_solve_rows`) from q0; where it does not converge, or converges with a
    cut's frames half a turn apart (the kernel's dot-product rows vanish there too: `assembly.flip`), a
    far phase on residuals without flipped solutions (`mechkit.core.assembly.from_far`) from q0 (and,
    where q0 is a stationary point of it, from seeded perturbations of q0: `_far_starts`), then the
    exact rows' solve again from there. Leaves `cd.pin` at q.

    Args:
        cm: the closure model.
        cd: its data (workspace; left at the solution).
        q0: (nq,) starting configuration; its given joints' coordinates are the inputs.
        split: which joints are given (`ClosureModel.split`).
        tol: residual norm to reach (m for position rows).
        max_iter: iteration cap of each exact solve.
        method: "newton" or "lm" for the exact rows.
        jacobian_at_trials: evaluate the Jacobian at every trial point (else only to step from an
            accepted one: cheaper when most steps are accepted at once, as along a path).

    Returns:
        The closed configuration q (nq,), the exact solve's iterations and its residual norm.

    Raises:
        ClosureNotConverged: the residual did not reach tol (the linkage may not assemble there).
    """
    try:
        out = _solve_rows(
            cm, cd, q0, split, tol=tol, max_iter=max_iter, method=method, jacobian_at_trials=jacobian_at_trials
        )
        turned = flip(cm, cd.pin)  # the exact solve leaves the placements at its q
        if turned <= FLIP_TOL:
            return out
        first = ClosureNotConverged(
            turned,
            FLIP_TOL,
            out.iterations,
            "the rows vanish with a cut's frames half a turn apart (a flipped closure), not closed",
        )
    except ClosureNotConverged as err:
        first = err
    best = first
    for start in _far_starts(cm, cd, q0, split):
        try:
            near = from_far(cm, cd, start, split)
            out = _solve_rows(
                cm, cd, near, split, tol=tol, max_iter=max_iter, method=method, jacobian_at_trials=jacobian_at_trials
            )
        except (ClosureNotConverged, np.linalg.LinAlgError) as err:
            if isinstance(err, ClosureNotConverged) and err.residual < best.residual:
                best = err
            continue
        if flip(cm, cd.pin) <= FLIP_TOL:
            return out
    raise best from None


def _far_starts(cm: ClosureModel, cd: ClosureData, q0: np.ndarray, split: InputSplit) -> list[np.ndarray]:
    """Where the far phase starts: q0, and where its residual is stationary there, `RESTARTS` seeded
    perturbations of the free coordinates (the given joints keep q0's values)."""
    e, J, _ = _far_rows(cm, cd, q0)
    Jf = J[:, split.free_v]
    if np.linalg.norm(Jf.T @ e) > STATIONARY_TOL * np.linalg.norm(Jf) * np.linalg.norm(e):
        return [q0]
    rng = np.random.default_rng(0)
    starts = [q0]
    for _ in range(RESTARTS):
        step = np.zeros(cm.model.nv)
        step[split.free_v] = rng.uniform(-RESTART_SIZE, RESTART_SIZE, split.free_v.size)
        starts.append(pin.integrate(cm.model, q0, step))
    return starts


def _solve_rows(
    cm: ClosureModel,
    cd: ClosureData,
    q0: np.ndarray,
    split: InputSplit,
    *,
    tol: float,
    max_iter: int,
    method: str,
    jacobian_at_trials: bool,
) -> Assembly:
    """The exact rows' solve: Gauss-Newton with a minimum-norm step (LAPACK gesv on a square regular
    block, else lstsq: redundant rows allowed) or Levenberg-Marquardt, both with a backtracking line
    search on |e|, stepping on the configuration manifold (`pin.integrate`), so any joint type works.

    Raises:
        ClosureNotConverged: the residual did not reach tol.
    """
    model, free_v = cm.model, split.free_v
    q = q0.copy()
    e, J, norm = _residual_and_jacobian(cm, cd, q, True)
    damping = 1e-3
    it = 0
    for it in range(max_iter):
        if norm <= tol:
            return Assembly(q, it, norm)
        if J is None:
            e, J, norm = _residual_and_jacobian(cm, cd, q, True)
        Jf = J[:, free_v]
        if method == "lm":
            step_free = -np.linalg.lstsq(Jf.T @ Jf + damping * np.eye(Jf.shape[1]), Jf.T @ e, rcond=None)[0]
        else:
            step_free = _newton_step(Jf, e)
        step = np.zeros(model.nv)
        step[free_v] = step_free
        alpha = 1.0
        while True:
            trial = pin.integrate(model, q, alpha * step)
            e_trial, J_trial, n_trial = _residual_and_jacobian(cm, cd, trial, jacobian_at_trials)
            if n_trial < norm or alpha < 1e-6:
                break
            alpha *= 0.5
        if not np.isfinite(n_trial):
            break
        if method == "lm":
            damping = damping * 0.3 if n_trial < norm else damping * 10.0
        q, e, J, norm = trial, e_trial, J_trial, n_trial
        if alpha < 1e-6 and norm > tol:
            break
    if norm <= tol:
        pin.forwardKinematics(model, cd.pin, q)
        return Assembly(q, it + 1, norm)
    raise ClosureNotConverged(
        float(norm),
        tol,
        it + 1,
        f"the loop cannot close from this guess, or at all, for these inputs; the widest gap: {_widest_gap(cm, e)}",
    )


def _widest_gap(cm: ClosureModel, e: np.ndarray) -> str:
    """The cut (or coupling) whose rows of the residual e (rows,) are largest, and their norm."""
    kernel = cm.kernel
    gaps = [
        (float(np.linalg.norm(e[rows])), f"loop {cut.closure.name!r}")
        for cut, rows in zip(kernel.cuts, kernel.cut_slices)
    ]
    gaps += [(abs(float(x)), f"coupling {c.coupling.name!r}") for c, x in zip(kernel.couplings, e[kernel.cut_size :])]
    size, what = max(gaps, default=(0.0, "none"))
    return f"{what} by {size:.3e}"
