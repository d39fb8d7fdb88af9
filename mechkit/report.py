"""`mechkit report`: structure, mobility and self-checks of one mechanism, as a dict (the JSON contract).

Top-level keys (a contract for scripts): name, nq, nv, actuated, closures [{name, kind, rows}], dof,
dof_gruebler, redundant_constraints, checks {name: worst residual or relative error}.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechkit.exceptions import MechkitError
from mechkit.mechanism import Mechanism


def _relative(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300))


def self_checks(m: Mechanism) -> dict[str, float]:
    """Core identities at the home assembly, with unit input rates and accelerations.

    closure_residual (m / -), velocity_constraint |J v|, acceleration_constraint |J a + gamma|,
    kkt_vs_proximal (relative, accelerations), inverse_forward_roundtrip (relative, accelerations),
    global_balance (relative: sum of support wrenches vs total gravity and inertia).
    """
    q = m.home_q
    checks: dict[str, float] = {"closure_residual": float(np.max(np.abs(m.closure_residual(q)), initial=0.0))}
    ones = np.ones(len(m.actuated))
    dof = m.mobility(q).dof
    if dof == len(m.actuated):
        v = m.velocities(q, ones)
        a = m.accelerations(q, v, 0.5 * ones)
        checks["velocity_constraint"] = float(np.max(np.abs(m.closure_jacobian(q) @ v), initial=0.0))
        checks["acceleration_constraint"] = float(np.max(np.abs(m.closure_jacobian(q) @ a + m.closure_drift(q, v)), initial=0.0))
    else:
        v = np.zeros(m.model.nv)
        a = m.forward_dynamics(q, v, np.zeros(m.model.nv), "kkt").a
    tau0 = np.zeros(m.model.nv)
    try:
        prox = m.forward_dynamics(q, v, tau0, "proximal").a
        kkt = m.forward_dynamics(q, v, tau0, "kkt").a
        checks["kkt_vs_proximal"] = _relative(prox, kkt)
    except MechkitError:
        pass  # method unavailable for this closure kind: reported by the absence of the check
    inv = m.inverse_dynamics(q, v, a)
    tau = np.zeros(m.model.nv)
    for joint, effort in inv.efforts.items():
        tau[m.v_index(joint)] = effort
    checks["inverse_forward_roundtrip"] = _relative(m.forward_dynamics(q, v, tau, "kkt").a, a)
    return checks | ({} if m.spec.self_checks is None else m.spec.self_checks(m))


def report(m: Mechanism) -> dict[str, Any]:
    """The report of a mechanism (see module docstring for the keys)."""
    mob = m.mobility()
    return {
        "name": m.spec.name,
        "summary": m.spec.summary,
        "nq": m.model.nq,
        "nv": m.model.nv,
        "actuated": list(m.actuated),
        "closures": [{"name": c.closure.name, "kind": c.closure.kind, "rows": c.size, "row_set": c.closure.rows}
                     for c in m.cuts],
        "dof": mob.dof,
        "dof_gruebler": m.spec.gruebler_dof,
        "redundant_constraints": mob.redundant,
        "parameters": [{k: v for k, v in row.items() if k != "positive"} for row in m.params.describe()],
        "home_q": [float(x) for x in m.home_q],
        "checks": self_checks(m),
    }


def format_report(r: dict[str, Any]) -> str:
    """Human-readable text of a report."""
    lines = [f"{r['name']}: {r['summary']}",
             f"  nq {r['nq']}, nv {r['nv']}, actuated: {', '.join(r['actuated'])}",
             "  closures: " + ", ".join(f"{c['name']} ({c['kind']}, {c['rows']} {c['row_set']} rows)" for c in r["closures"]),
             f"  DOF numerical {r['dof']}, Gruebler {r['dof_gruebler']}, redundant constraints {r['redundant_constraints']}",
             "  parameters:"]
    for p in r["parameters"]:
        mark = " (ours)" if p.get("ours") else ""
        lines.append(f"    {p['name']:<18} {p['value']!s:>12} {p['unit']:<8} {p['doc']}{mark}")
    lines.append("  self-checks (worst residual or relative error):")
    for name, value in r["checks"].items():
        lines.append(f"    {name:<32} {value:.3e}")
    return "\n".join(lines)
