"""The 9RR-12URU deployable composite element (Xu et al. 2017, references/003, Fig. 1).

Three 3RR-3URU units H-ABE, J-AFC, I-ADG (`tetra_3rr3uru`) share the fixed node A, turned by 0,
-120 and +120 deg about z (eq. 8), joined by the URU constraint chains EC, DF, BG: 43 bodies of the
paper plus 24 Hooke crosses, 66 tree coordinates, 12 cuts of 5 rows = 60 rows, rank 59 along the
paper's (three-fold symmetric) motions: 7 DOF with one redundant constraint (eq. 5); to second order
the seventh DOF holds only along those motions (`second_order_form`). Drives (section 3.2): fold at H, J, I (web rods AH, AJ, AI),
attitude at B, F, G (web rods BH, FJ, GI) and web rod EH at H (see `ACTUATED`);
`tetra_3rr3uru.web_joint_motion` gives their joint laws.

Scene: `fold` (the 200 s fold, closure solved along it by continuation; `SCENES` for snapshots).
Analysis: `redundancy` (the self-stress), `mobility_without` (chains removed),
`indeterminate_direction` (the indeterminate part of the reactions), `second_order_form`,
`fold_checks` (rows of `mechkit report`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import pinocchio as pin

from mechkit.exceptions import InvalidParameters
from mechkit.mechanisms.tetra_3rr3uru import TetraParams, drive_inputs
from mechkit.mechanisms.truss_geometry import FOLD_DURATION, drive_state
from mechkit.params import param
from mechkit.contract import MechanismSpec

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

#: Fold at H, J, I and attitude at B, F, G as in the paper; rod EH at H in place of the attitude drive
#: at E (B and E attitudes are tied to first order in this model, see `tetra_3rr3uru.ACTUATED`).
ACTUATED = ("AH_H", "AJ_J", "AI_I", "BH_B", "FJ_F", "GI_G", "EH_H")
NODES = ("A", "B", "C", "D", "E", "F", "G", "H", "I", "J")


@dataclass(frozen=True)
class DeployableParams(TetraParams):
    l3: float = param(0.250, "m", "each link of the constraint chains EC, DF, BG (paper silent; = l2)", ours=True)

    def validate(self) -> None:
        super().validate()
        nodes = self.geometry().node_positions(self.alpha_ref, self.gamma_ref)
        for chain in ("EC", "DF", "BG"):
            chord = float(np.linalg.norm(nodes[chain[1]] - nodes[chain[0]]))
            if chord >= 2.0 * self.l3:
                raise InvalidParameters("l3", self.l3, f"chain {chain} cannot reach: chord {chord:.4f} m >= 2 l3")


@dataclass(frozen=True)
class FoldSample:
    """One instant of the fold: time (s), q, v, a, and the solver iterations it took."""

    t: float
    q: np.ndarray
    v: np.ndarray
    a: np.ndarray
    iterations: int


def apexes(mech: Mechanism) -> tuple[str, ...]:
    """Unit apexes present in the model (H for the unit; H, J, I for the composite)."""
    return tuple(a for a in ("H", "J", "I") if mech.model.existJointName(f"A{a}_{a}"))


def _fold_step(mech: Mechanism, q: np.ndarray, v: np.ndarray, t_prev: float, t: float, tol: float,
               depth: int = 0) -> FoldSample:
    """Closure solve at t from the state (q, v) at t_prev: predictor q + v dt, then Newton on the
    passive coordinates; the interval is halved (up to 8 times) when Newton does not converge."""
    from mechkit import kinematics
    from mechkit.exceptions import ClosureNotConverged

    s = drive_state(t)
    angles, rates, accs = drive_inputs(mech.params, s, mech.actuated, apexes(mech))
    guess = pin.integrate(mech.model, q, v * (t - t_prev))
    for joint, value in angles.items():
        guess[mech.q_index(joint)] = value
    free = np.setdiff1d(np.arange(mech.model.nv), [mech.v_index(j) for j in angles])
    try:
        q_new, iterations = kinematics.solve_closure(mech.rows, mech.data, guess, free, tol=tol)
    except ClosureNotConverged:
        if depth >= 8:
            raise
        half = _fold_step(mech, q, v, t_prev, 0.5 * (t_prev + t), tol, depth + 1)
        return _fold_step(mech, half.q, half.v, half.t, t, tol, depth + 1)
    v_new = mech.velocities(q_new, rates, list(rates))
    return FoldSample(float(t), q_new, v_new, mech.accelerations(q_new, v_new, accs, list(accs)), iterations)


def fold(mech: Mechanism, times: np.ndarray, tol: float = 1e-12) -> list[FoldSample]:
    """The paper's fold: drive laws alpha(t), gamma(t) on every drive, closure solved at each time.

    Continuation from the reference configuration (t = 0): each solve starts from the previous
    state advanced by v dt (first-order predictor), with interval halving when a step is too long.
    Velocities and accelerations are the closure projections of the drive rates and accelerations.

    Args:
        mech: `tetra_3rr3uru` or `deployable_9rr12uru`.
        times: increasing times in [0, 200] s.
        tol: closure residual to reach (m / dimensionless).
    """
    times = np.asarray(times, dtype=float)
    if times.ndim != 1 or times.size == 0 or np.any(np.diff(times) <= 0):
        raise InvalidParameters("times", times, "must be a non-empty, strictly increasing 1-D array")
    out: list[FoldSample] = []
    state = _fold_step(mech, mech.home_q, np.zeros(mech.model.nv), 0.0, 0.0, tol)
    for t in times:
        state = _fold_step(mech, state.q, state.v, state.t, float(t), tol)
        out.append(state)
    return out


def node_positions(mech: Mechanism, q: np.ndarray) -> dict[str, np.ndarray]:
    """World positions (m) of the node centres in the model at q (Pinocchio forward kinematics)."""
    pin.forwardKinematics(mech.model, mech.data, q)
    pin.updateFramePlacements(mech.model, mech.data)
    out = {}
    for node in NODES:
        name = f"node_{node}"
        if mech.model.existFrame(name):
            out[node] = mech.data.oMf[mech.model.getFrameId(name)].translation.copy()
    return out


def node_velocity(mech: Mechanism, q: np.ndarray, v: np.ndarray, node: str) -> np.ndarray:
    """World velocity (m/s) of a node centre in the model at (q, v)."""
    frame = f"node_{node}"
    if not mech.model.existFrame(frame):
        raise InvalidParameters("node", node, f"no node {node} in {mech.spec.name}")
    pin.forwardKinematics(mech.model, mech.data, q, v)
    velocity = pin.getFrameVelocity(mech.model, mech.data, mech.model.getFrameId(frame), pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
    return velocity.linear.copy()


COMPONENTS = ("fx", "fy", "fz", "mx", "my", "mz")


def indeterminate_reactions(result) -> dict[str, tuple[str, ...]]:
    """Joint -> world reaction components that statics leaves undetermined (from the determinacy
    flags of `Mechanism.inverse_dynamics`); joints whose reaction is fully determinate are absent."""
    if any(r.determinate is None for r in result.reactions.values()):
        raise InvalidParameters("result", "determinacy=False", "run Mechanism.inverse_dynamics with determinacy=True")
    return {joint: tuple(c for c, ok in zip(COMPONENTS, r.determinate) if not ok)
            for joint, r in result.reactions.items() if not r.determinate.all()}


@dataclass(frozen=True)
class Redundancy:
    """The redundant constraint of the composite at one configuration.

    Attributes:
        singular_values: of the closure Jacobian (descending).
        self_stress: cut name -> (force (N), moment (N m)) world, at the middle hinge, of the unit
            left null vector y of the closure Jacobian (J^T y = 0): the constraint forces that
            balance among themselves, i.e. the direction in which the reactions are indeterminate.
            Each share is a force along the cut's middle hinge (plus, once folding has started, a
            moment normal to it).
        hinge_axes: cut name -> unit middle-hinge axis (world).
    """

    singular_values: np.ndarray
    self_stress: dict[str, tuple[np.ndarray, np.ndarray]]
    hinge_axes: dict[str, np.ndarray]


def _self_stress(mech: Mechanism, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Singular values of the closure Jacobian at q and its last left singular vector y (J^T y = 0),
    signed so that its largest entry is positive. Leaves mech.data at q."""
    U, s, _ = np.linalg.svd(mech.closure_jacobian(q))
    y = U[:, -1]
    return s, y * np.sign(y[np.argmax(np.abs(y))])


def redundancy(mech: Mechanism, q: np.ndarray) -> Redundancy:
    """Self-stress of the composite at q: the redundant combination of closure rows."""
    s, y = _self_stress(mech, q)
    stress, axes = {}, {}
    for cut, (f, m, _) in zip(mech.rows.cuts, mech.rows.wrenches(mech.data, y)):
        stress[cut.closure.name] = (f, m)
        axes[cut.closure.name] = mech.data.oMf[cut.frame_a].rotation @ cut.closure.axis
    return Redundancy(s, stress, axes)


def indeterminate_direction(mech: Mechanism, q: np.ndarray) -> dict[str, np.ndarray]:
    """The one-dimensional indeterminate part of the reactions at q, made explicit.

    Every reaction is R = R_0 + s P with s undetermined by statics: P (joint -> (6,) world wrench,
    parent on child, at the joint point) is the set of reactions that the self-stress alone
    produces (its closure forces applied to the tree, no gravity, no motion), scaled so that
    max |P| = 1. Components where P vanishes are the determinate ones.
    """
    from mechkit.dynamics import cut_wrench_arrays, subtract_cut_wrenches, subtree_incidence

    _, y = _self_stress(mech, q)
    model = mech.model
    G = subtree_incidence(model, mech.rows)
    W, P = cut_wrench_arrays(mech.data, mech.rows, y)
    tree = subtract_cut_wrenches(np.zeros((model.njoints, 6)), mech.data, np.flatnonzero(np.any(G != 0, axis=1)), G, W, P)
    pattern = {model.names[i]: tree[i] for i in range(1, model.njoints)}
    pattern |= {c.closure.name: w for c, w in zip(mech.rows.cuts, W)}
    scale = max(np.abs(v).max() for v in pattern.values())
    return {joint: v / scale for joint, v in pattern.items()}


def second_order_form(mech: Mechanism, q: np.ndarray, h: float = 1e-3) -> tuple[np.ndarray, np.ndarray]:
    """Second-order test of the redundant configuration q: Q(d) = y^T e''(q)[d, d] on ker J.

    y is the self-stress (J^T y = 0), e the closure residual. A first-order motion d (J d = 0)
    continues to a motion only if Q(d) = 0, so the instantaneous DOF count holds for finite motions
    only along the zero set of Q. Central differences with step h (rad, m) on the residual.

    Returns:
        ((k, k) matrix of Q, (nv, k) orthonormal basis of ker J in which it is written).
    """
    from scipy.linalg import null_space

    _, y = _self_stress(mech, q)
    basis = null_space(mech.closure_jacobian(q), rcond=1e-9)

    def along(d: np.ndarray) -> float:
        return float(y @ mech.closure_residual(pin.integrate(mech.model, q, d)))

    k = basis.shape[1]
    Q = np.zeros((k, k))
    for i in range(k):
        for j in range(i, k):
            a, b = h * basis[:, i], h * basis[:, j]
            Q[i, j] = Q[j, i] = (along(a + b) - along(a - b) - along(b - a) + along(-a - b)) / (4.0 * h * h)
    return Q, basis


def chain_joints(chain: str) -> tuple[str, ...]:
    """Tree joints of a URU rod or chain (e.g. "BG": BG_B1, BG_B2, BG_G1, BG_G2)."""
    return tuple(f"{chain}_{node}{k}" for node in chain for k in (1, 2))


def mobility_without(mech: Mechanism, q: np.ndarray, chains: tuple[str, ...]) -> tuple[int, int]:
    """(DOF, redundant rows) of the composite at q with the given URU chains removed."""
    from mechkit.kinematics import numerical_rank

    J = mech.closure_jacobian(q)
    drop_cols = [mech.v_index(j) for c in chains for j in chain_joints(c)]
    keep_rows, i = [], 0
    for cut in mech.rows.cuts:
        if cut.closure.name[:-2] not in chains:
            keep_rows += list(range(i, i + cut.size))
        i += cut.size
    sub = np.delete(J[keep_rows], drop_cols, axis=1)
    rank = numerical_rank(np.linalg.svd(sub, compute_uv=False))
    return sub.shape[1] - rank, sub.shape[0] - rank


#: Instants of the fold sampled by `fold_checks`, s.
CHECK_TIMES = (0.0, 100.0, 200.0)


def fold_checks(mech: Mechanism, times: tuple[float, ...] = CHECK_TIMES) -> dict[str, float]:
    """Worst deviations along the fold (rows of `mechkit report`): node positions against eq. (6)-(8)
    (m), closure residual, and, for the unit, SOC against the constrained RNEA (relative)."""
    g = mech.params.geometry()
    worst = {"fold: node positions vs eq. (6)-(8) (m)": 0.0, "fold: closure residual": 0.0}
    for sample in fold(mech, np.asarray(times)):
        s = drive_state(sample.t)
        expected = g.node_positions(s.alpha, s.gamma)
        error = max(np.abs(p - expected[n]).max() for n, p in node_positions(mech, sample.q).items())
        worst["fold: node positions vs eq. (6)-(8) (m)"] = max(worst["fold: node positions vs eq. (6)-(8) (m)"], error)
        worst["fold: closure residual"] = max(worst["fold: closure residual"], np.abs(mech.closure_residual(sample.q)).max())
        if mech.spec.name == "tetra_3rr3uru":
            from mechkit.mechanisms import tetra_3rr3uru_soc

            reference = mech.inverse_dynamics(sample.q, sample.v, sample.a)
            result = tetra_3rr3uru_soc.solve(mech, sample.t)
            scale = max(np.abs(r.wrench).max() for r in reference.reactions.values())
            error = max(np.abs(result.reactions[j] - r.wrench).max() for j, r in reference.reactions.items()) / scale
            key = "SOC vs constrained RNEA, reactions (rel)"
            worst[key] = max(worst.get(key, 0.0), error)
    return worst


def fold_times(step: float = 1.0) -> np.ndarray:
    """Sample times of the 200 s fold, s."""
    if not 0.0 < step <= FOLD_DURATION:
        raise InvalidParameters("step", step, f"must lie in (0, {FOLD_DURATION}] s")
    return np.linspace(0.0, FOLD_DURATION, round(FOLD_DURATION / step) + 1)


def fold_poses(mech: Mechanism) -> list[np.ndarray]:
    """The 200 s fold sampled every 1 s: 201 assembled configurations (the "fold" scene)."""
    return [s.q for s in fold(mech, fold_times(1.0))]


#: Animated scenes for `mechkit snapshot --scene` (scene name -> poses).
SCENES = {"fold": fold_poses}

SPEC = MechanismSpec(
    name="deployable_9rr12uru",
    params=DeployableParams,
    template="deployable_9rr12uru.urdf.xacro",
    actuated=ACTUATED,
    gruebler_dof=7,
    home=lambda p: {joint: 0.0 for joint in ACTUATED},
    summary="9RR-12URU deployable composite element of a truss antenna (3 tetrahedral units + 3 URU chains)",
    self_checks=fold_checks,
)
