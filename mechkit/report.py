"""`mechkit report`: structure, mobility and self-checks of one mechanism, as a dict (the JSON contract).

Top-level keys (a contract for scripts): name, nq, nv, actuated, closures [{name, kind, rows}], dof,
dof_gruebler, redundant_constraints, checks {name: worst residual or relative error}; and refused
{check: why the core refused it there (e.g. a near-singular pose)}, holding {efforts: {actuator: effort
holding gravity at rest, N m or N}} or {refused: why the actuators cannot}, idle {body: its idle
freedoms}, loops [{cut, kind (planar / spherical / spatial), rows, full_rows, chosen}], rows_avoided,
gruebler {kutzbach, declared}, home {joint: value}.

`dof_gruebler` is the loop-by-loop Kutzbach count of the topology (`mechkit.core.structure`); a
registered mechanism's declared count (its spec) is shown beside it: the two differ only where the
declared count is a modified one with overconstraints found by screw theory at a configuration (the
deployable 9RR-12URU: 6 from topology, 7 declared with one redundant constraint).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechkit.base.exceptions import MechkitError
from mechkit.mechanism import Mechanism

#: Largest accepted self-check value (worst residual, m or rad, or relative error; ours): the registry's
#: defaults stay below 3e-9 (the rocket gimbal's printed lengths), a parameter set that breaks a
#: mechanism's own source kinematics lands far above (tetra_3rr3uru gamma_ref=0.0623: 0.39 m).
CHECK_LIMIT = 1e-6


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


def self_checks(m: Mechanism) -> tuple[dict[str, float], dict[str, str]]:
    """Core identities at the home assembly, with unit input rates and accelerations.

    closure_residual (m / -), velocity_constraint |J v|, acceleration_constraint |J a + gamma|,
    kkt_vs_proximal (relative, accelerations), inverse_forward_roundtrip (relative, accelerations),
    and the spec's own checks.

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
            checks["velocity_constraint"] = float(np.max(np.abs(m.closure_jacobian(q) @ v), initial=0.0))
            checks["acceleration_constraint"] = float(np.max(np.abs(m.closure_jacobian(q) @ a + m.closure_drift(q, v)),
                                                            initial=0.0))
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


def holding(m: Mechanism) -> dict[str, Any]:
    """The actuator efforts that hold the mechanism still at home under gravity and its springs, or why
    they cannot (unactuated, a floating base, a motion the actuators do not span).

    Args:
        m: the mechanism.

    Returns:
        {"efforts": actuator -> effort (N m or N)} or {"refused": the reason}.
    """
    if not m.actuated:
        return {"refused": "unactuated: no actuator to hold it"}
    zero = np.zeros(m.model.nv)
    try:
        return {"efforts": m.inverse_dynamics(m.home_q, zero, zero, determinacy=False).efforts}
    except MechkitError as err:
        return {"refused": str(err)}


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
        "home": m.joint_values(m.home_q),
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
    return "\n".join(lines)
