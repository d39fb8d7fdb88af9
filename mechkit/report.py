"""`mechkit report`: structure, mobility and self-checks of one mechanism, as a dict (the JSON contract).

Top-level keys (a contract for scripts): name, nq, nv, actuated, closures [{name, kind, rows}], dof,
dof_gruebler, redundant_constraints, checks {name: worst residual or relative error}; and refused
{check: why the core refused it there (e.g. a near-singular pose)}, holding {efforts: {actuator: effort
holding gravity at rest, N m or N}, undetermined: [actuators whose effort statics does not fix], q:
the configuration they hold, settled: {joint: its value there} for the joints that settled away from
home} or {refused: why the actuators cannot}, idle {body: its
idle freedoms}, loops [{cut, kind (planar / spherical / spatial), rows, full_rows, chosen}],
rows_avoided, gruebler {kutzbach, declared}, home {joint: value}.

Holding at rest: the actuators hold their joints at home; what they do not drive (joints on springs,
rods spinning about their own axes) settles where the load on it vanishes (`settle`), and the efforts
are those that hold that configuration. A floating root, a load nothing balances and a pose where the
inputs do not determine the motion are refused, each by name.

`dof_gruebler` is the loop-by-loop Kutzbach count of the topology (`mechkit.core.structure`); a
registered mechanism's declared count (its spec) is shown beside it: the two differ only where the
declared count is a modified one with overconstraints found by screw theory at a configuration (the
deployable 9RR-12URU: 6 from topology, 7 declared with one redundant constraint).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
import pinocchio as pin
import scipy.linalg

from mechkit import core
from mechkit.base.exceptions import ClosureNotConverged, MechkitError, SingularConfiguration
from mechkit.mechanism import Mechanism

#: Largest accepted self-check value (worst residual, m or rad, or relative error; ours): the registry's
#: defaults stay below 3e-9 (the rocket gimbal's printed lengths), a parameter set that breaks a
#: mechanism's own source kinematics lands far above (tetra_3rr3uru gamma_ref=0.0623: 0.39 m).
CHECK_LIMIT = 1e-6
#: Largest load left along the motions no actuator drives at a settled configuration, relative to the
#: largest generalised load (absolute below 1 N m): a tenth of what the inverse dynamics accepts as held
#: there (1e-9), so that the efforts are not refused for it; above the rounding of that load at a closed
#: configuration (1e-12 on Gepetto's five-bar, whose end spheres weigh 654 t; ours).
SETTLE_TOL = 1e-10
#: Newton steps `settle` takes before it gives up (ours: the field's robots settle in under ten).
SETTLE_STEPS = 50
#: Central-difference step of the settling Hessian (rad or m along unit motions; ours).
SETTLE_STEP = 1e-6
#: A joint whose value changed by more than this (rad or m) while settling is listed as settled (ours:
#: above the closure's own scatter, 1e-12).
SETTLED = 1e-9


def failing_checks(checks: dict[str, float], limit: float = CHECK_LIMIT) -> dict[str, float]:
    """The checks above `limit`, or not finite.

    Args:
        checks: check name -> worst residual or relative error.
        limit: the threshold.

    Returns:
        The failing checks, name -> value.
    """
    return {k: v for k, v in checks.items() if not v <= limit}


def _relative(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300))


def _scaled(residual: np.ndarray, *terms: float) -> float:
    """max |residual|, divided by the largest term where that exceeds 1."""
    return float(np.max(np.abs(residual), initial=0.0) / max(1.0, *terms))


def self_checks(m: Mechanism) -> tuple[dict[str, float], dict[str, str]]:
    """Core identities at the home assembly, with unit input rates and accelerations.

    closure_residual (m / -), velocity_constraint |J v| and acceleration_constraint |J a + gamma|
    (absolute, and relative to the largest of their terms |J| |v|, |J a|, |gamma| where that exceeds 1:
    near a singular pose unit inputs drive passive joints at thousands of rad/s), kkt_vs_proximal
    (relative, accelerations), inverse_forward_roundtrip (relative, accelerations), and the spec's own
    checks.

    Args:
        m: the mechanism.

    Returns:
        The checks' values (worst residual or relative error; smaller is better), and by name the checks
        the core refused to compute (a `MechkitError`: a near-singular pose, a method that cannot express
        a closure kind), with the reason.
    """
    q = m.home_q
    checks: dict[str, float] = {"closure_residual": float(np.max(np.abs(m.closure_residual(q)), initial=0.0))}
    refused: dict[str, str] = {}
    if not m.actuated:
        return checks, refused  # the other checks drive the actuators

    def attempt(name: str, fn) -> Any:
        try:
            return fn()
        except MechkitError as err:
            refused[name] = str(err)
            return None

    ones = np.ones(len(m.actuated))
    v, a = np.zeros(m.model.nv), None

    def driven() -> tuple[np.ndarray, np.ndarray]:
        rates = m.velocities(q, ones)
        return rates, m.accelerations(q, rates, 0.5 * ones)

    if m.mobility(q).dof == len(m.actuated):
        state = attempt("velocity_constraint", driven)
        if state is not None:
            v, a = state
            J, gamma = m.closure_jacobian(q), m.closure_drift(q, v)
            checks["velocity_constraint"] = _scaled(J @ v, np.max(np.abs(J), initial=0.0) * np.max(np.abs(v)))
            checks["acceleration_constraint"] = _scaled(J @ a + gamma, np.max(np.abs(J @ a), initial=0.0),
                                                        np.max(np.abs(gamma), initial=0.0))
    if a is None:
        a = attempt("forward_dynamics", lambda: m.forward_dynamics(q, v, np.zeros(m.model.nv), "kkt").a)
    tau0 = np.zeros(m.model.nv)
    both = attempt("kkt_vs_proximal", lambda: (m.forward_dynamics(q, v, tau0, "proximal").a,
                                               m.forward_dynamics(q, v, tau0, "kkt").a))
    if both is not None:
        checks["kkt_vs_proximal"] = _relative(*both)
    if a is not None:
        back = attempt("inverse_forward_roundtrip", lambda: m.forward_dynamics(
            q, v, m.generalized_forces(m.inverse_dynamics(q, v, a).efforts), "kkt").a)
        if back is not None:
            checks["inverse_forward_roundtrip"] = _relative(back, a)
    return checks | ({} if m.spec.self_checks is None else m.spec.self_checks(m)), refused


def _plain(values: dict[str, Any]) -> dict[str, float | list[float]]:
    """Joint values as JSON numbers: a float, or a list for a joint of several coordinates."""
    return {j: float(v) if np.ndim(v) == 0 else [float(x) for x in np.ravel(v)] for j, v in values.items()}


def held_joints(m: Mechanism) -> tuple[str, ...]:
    """The joints the actuators act on, held still at rest: a motor's joint, each joint of a tendon."""
    tendons = {a.name: a for a in m.closure_model.actuators}
    joints = [j for name in m.actuated for j in ([j for j, _ in tendons[name].joints] if name in tendons else [name])]
    return tuple(dict.fromkeys(joints))


def undriven_motions(m: Mechanism, q: np.ndarray, held: Sequence[str]) -> np.ndarray:
    """(nv, d) orthonormal basis of the motions at q (nq,) that close every loop and move no `held` joint
    (rank judged as the core judges it, `mechkit.core.RANK_TOL`)."""
    select = np.zeros((len(held), m.model.nv))
    for k, joint in enumerate(held):
        select[k, m.v_index(joint)] = 1.0
    return scipy.linalg.null_space(np.vstack([m.closure_jacobian(q), select]), rcond=core.RANK_TOL)


def rest_load(m: Mechanism, q: np.ndarray) -> np.ndarray:
    """(nv,) the generalised force (N m or N) the joints must supply to hold q (nq,) at rest: gravity
    minus the springs, the gradient of `potential_energy`."""
    g = pin.computeGeneralizedGravity(m.model, m.data, q).copy()
    passive = m.passive_forces(q, np.zeros(m.model.nv))
    return g if passive is None else g - passive


def potential_energy(m: Mechanism, q: np.ndarray) -> float:
    """The potential energy (J) of gravity and the joint springs at q (nq,)."""
    gravity = float(pin.computePotentialEnergy(m.model, m.data, q))
    return gravity + (float(m.springs.potential(q)) if m.springs else 0.0)


def settle(m: Mechanism, q: np.ndarray) -> np.ndarray:
    """The configuration near q (nq,) where the motions no actuator drives carry no load: the actuators'
    joints held at their values in q, every loop closed, the potential energy (gravity and springs) at a
    minimum along the undriven motions (`undriven_motions`: joints on springs, rods spinning about their
    own axes).

    Newton on the load along those motions, U^T (g - f_springs), its Hessian by central differences of
    `SETTLE_STEP` along them (made positive definite, so that each step lowers the energy), steps shortened
    until the energy falls, each configuration closed again (`Mechanism.solve_closure`), until that load
    is below `SETTLE_TOL` of the largest generalised load. q itself when no undriven motion is loaded.

    Returns:
        (nq,) the settled configuration.

    Raises:
        MechkitError: the undriven motions do not settle within `SETTLE_STEPS` steps (a load nothing
            balances, e.g. a passive slide under gravity), naming the joints they move.
        ClosureNotConverged: a loop does not close along the way.
    """
    held = held_joints(m)

    def along(U: np.ndarray, q: np.ndarray) -> np.ndarray:  # U^T P(q) load(q), P the projector on q's undriven motions
        here = undriven_motions(m, q, held)
        return U.T @ (here @ (here.T @ rest_load(m, q)))

    def moved(q: np.ndarray, step: np.ndarray) -> np.ndarray:
        return m.solve_closure(pin.integrate(m.model, q, step), held).q

    with np.errstate(under="ignore"):
        for _ in range(SETTLE_STEPS):
            U = undriven_motions(m, q, held)
            load = rest_load(m, q)
            G = U.T @ load
            scale = max(1.0, float(np.max(np.abs(load))))
            if U.shape[1] == 0 or np.max(np.abs(G)) <= SETTLE_TOL * scale:
                return q
            H = np.column_stack([(along(U, moved(q, SETTLE_STEP * u)) - along(U, moved(q, -SETTLE_STEP * u)))
                                 / (2 * SETTLE_STEP) for u in U.T])
            w, V = np.linalg.eigh(0.5 * (H + H.T))
            w = np.maximum(np.abs(w), 1e-9 * max(float(np.max(np.abs(w))), scale))
            dz = -V @ ((V.T @ G) / w)
            before, t = potential_energy(m, q), 1.0
            while t > 1e-9:
                try:
                    trial = moved(q, t * (U @ dz))
                except ClosureNotConverged:
                    t *= 0.5
                    continue
                if potential_energy(m, trial) <= before or np.max(np.abs(along(U, trial))) < np.max(np.abs(G)):
                    q = trial
                    break
                t *= 0.5
            else:
                break
    joints = [m.model.names[j] for j in range(1, m.model.njoints)
              if np.max(np.abs(U[m.model.joints[j].idx_v:m.model.joints[j].idx_v + m.model.nvs[j]]), initial=0.0) > 0.1]
    raise MechkitError(f"the motions no actuator drives do not settle: after {SETTLE_STEPS} steps they still carry "
                       f"{np.max(np.abs(G)):.3e} (N m or N) of load, moving {', '.join(joints)}")


def outside_range(m: Mechanism, q: np.ndarray, start: np.ndarray) -> str:
    """The first one-freedom joint that moved from `start` to q (both (nq,)) and lies at q outside the
    range its file declares (the model's position limits, where lower < upper: a URDF joint without
    bounds has 0, 0) by more than `SETTLED`, in words (its value and range, rad or m), else ""."""
    model = m.model
    for j in range(1, model.njoints):
        if model.nqs[j] != 1:
            continue
        i = model.joints[j].idx_q
        low, high = model.lowerPositionLimit[i], model.upperPositionLimit[i]
        if low < high and abs(q[i] - start[i]) > SETTLED and not low - SETTLED <= q[i] <= high + SETTLED:
            return f"{model.names[j]} at {q[i]:.6g}, outside its range [{low:.6g}, {high:.6g}]"
    return ""


def _weakest_motion(m: Mechanism, q: np.ndarray) -> str:
    """The joints the passive block's weakest determined motion at q turns most, and its singular value."""
    basis = m.closure_model.unactuated
    _, s, vt = np.linalg.svd(m.closure_jacobian(q) @ basis)
    k = min(len(s), m.independent_rows) - 1
    v = basis @ vt[k]
    size = {m.model.names[j]: float(np.linalg.norm(v[m.model.joints[j].idx_v:m.model.joints[j].idx_v + m.model.nvs[j]]))
            for j in range(1, m.model.njoints)}
    top = sorted((n for n, x in size.items() if x > 0.1 * max(size.values())), key=lambda n: -size[n])
    return f"the weakest passive motion (singular value {s[k]:.2e}) turns {', '.join(top)}"


def holding(m: Mechanism) -> dict[str, Any]:
    """The actuator efforts that hold the mechanism still under gravity and its springs, the actuators at
    home and the motions they do not drive settled (`settle`), or why they cannot: unactuated, a
    floating root, a load that does not settle, a pose where the inputs do not determine the motion.

    Args:
        m: the mechanism.

    Returns:
        {"efforts": {actuator: effort (N m or N)}, "undetermined": the actuators whose effort statics
        does not fix (redundant actuation: the efforts given are the least-norm ones), "q": the
        configuration held (nq,), "settled": {joint: value (rad or m; a ball's rotation vector)} of
        the joints that moved from home}, or {"refused": why}.
    """
    if not m.actuated:
        return {"refused": "unactuated: no actuator to hold it"}
    model = m.model
    roots = [j for j in range(1, model.njoints) if model.parents[j] == 0 and model.joints[j].shortname() == "JointModelFreeFlyer"]
    if roots:
        body = core.body_name(model, roots[0])
        return {"refused": f"floating root {model.names[roots[0]]!r}: nothing holds its weight (fix its body: --fix {body})"}
    zero = np.zeros(model.nv)
    try:
        q = settle(m, m.home_q)
    except MechkitError as err:
        return {"refused": str(err)}
    stop = outside_range(m, q, m.home_q)
    if stop:
        return {"refused": f"the joints no actuator drives settle against a stop: {stop} (mechkit does not model "
                           "joint stops)"}
    try:
        result = m.inverse_dynamics(q, zero, zero)
    except SingularConfiguration as err:
        return {"refused": f"{err}: {_weakest_motion(m, q)}"}
    except MechkitError as err:
        return {"refused": str(err)}
    home, there = m.joint_values(m.home_q), _plain(m.joint_values(q))
    settled = {j: v for j, v in there.items() if np.max(np.abs(np.subtract(v, home[j]))) > SETTLED}
    return {"efforts": result.efforts, "undetermined": [a for a in m.actuated if not result.efforts_determinate[a]],
            "q": [float(x) for x in q], "settled": settled}


def report(m: Mechanism) -> dict[str, Any]:
    """The report of a mechanism (see module docstring for the keys).

    Args:
        m: the mechanism.

    Returns:
        The report (the JSON contract: see the module docstring for the keys).
    """
    mob = m.mobility()
    declared = None if m.spec.template == "" else m.spec.gruebler_dof
    checks, refused = self_checks(m)
    return {
        "name": m.spec.name,
        "summary": m.spec.summary,
        "nq": m.model.nq,
        "nv": m.model.nv,
        "actuated": list(m.actuated),
        "closures": [{"name": c.closure.name, "kind": c.closure.kind, "rows": c.size, "row_set": c.closure.rows}
                     for c in m.cuts],
        "dof": mob.dof,
        "dof_gruebler": m.structure.kutzbach,
        "redundant_constraints": mob.redundant,
        "idle": dict(m.idle),
        "loops": [{"cut": lp.cut, "kind": lp.kind, "rows": lp.rows, "full_rows": lp.full_rows, "chosen": lp.chosen}
                  for lp in m.structure.loops],
        "rows_avoided": m.structure.rows_avoided,
        "gruebler": {"kutzbach": m.structure.kutzbach, "declared": declared},
        "home": _plain(m.joint_values(m.home_q)),
        "parameters": [{k: v for k, v in row.items() if k != "positive"} for row in m.params.describe()],
        "home_q": [float(x) for x in m.home_q],
        "checks": checks,
        "refused": refused,
        "holding": holding(m),
    }


def format_report(r: dict[str, Any]) -> str:
    """Human-readable text of a report.

    Args:
        r: a report.

    Returns:
        The text, lines joined.
    """
    lines = [f"{r['name']}: {r['summary']}",
             f"  nq {r['nq']}, nv {r['nv']}, actuated: {', '.join(r['actuated']) or 'none (unactuated)'}",
             "  closures: " + ", ".join(f"{c['name']} ({c['kind']}, {c['rows']} {c['row_set']} rows)" for c in r["closures"]),
             f"  DOF numerical {r['dof']}, Gruebler {r['dof_gruebler']}, redundant constraints {r['redundant_constraints']}"
             + (f" (declared Gruebler {r['gruebler']['declared']})" if r["gruebler"]["declared"] not in (None, r["dof_gruebler"]) else ""),
             "  idle freedoms: " + (", ".join(f"{j} {n}" for j, n in r["idle"].items()) or "none"),
             "  loops: " + ", ".join(f"{lp['cut']} {lp['kind']} {lp['rows']}/{lp['full_rows']} rows ({lp['chosen']})"
                                     for lp in r["loops"]) + f"; {r['rows_avoided']} rows avoided"]
    if r["parameters"]:
        lines.append("  parameters:")
    for p in r["parameters"]:
        mark = " (ours)" if p.get("ours") else ""
        lines.append(f"    {p['name']:<18} {p['value']!s:>12} {p['unit']:<8} {p['doc']}{mark}")
    lines.append("  self-checks (worst residual or relative error):")
    for name, value in r["checks"].items():
        lines.append(f"    {name:<32} {value:.3e}")
    for name, why in r["refused"].items():
        lines.append(f"    {name:<32} refused: {why}")
    held = r["holding"]
    lines.append("  holding gravity at rest: " + (", ".join(f"{j} {u:.6g}" for j, u in held["efforts"].items())
                                                  if "efforts" in held else f"the actuators cannot ({held['refused']})"))
    if held.get("undetermined"):
        lines.append("    not fixed by statics (least-norm shares): " + ", ".join(held["undetermined"]))
    if held.get("settled"):
        lines.append("    with the undriven joints settled at: " + ", ".join(
            f"{j} {np.array2string(np.asarray(v), precision=6)}" for j, v in held["settled"].items()))
    return "\n".join(lines)
