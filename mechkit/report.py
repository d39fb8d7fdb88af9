"""`mechkit report`: structure, mobility and self-checks of one mechanism, as a dict (the JSON contract).

Top-level keys (a contract for scripts): name, nq, nv, actuated, closures [{name, kind, rows}], dof,
dof_gruebler, redundant_constraints, checks {name: worst residual or relative error}; and refused
{check: why the core refused it there (e.g. a near-singular pose)}, holding {efforts: {actuator: effort
holding gravity at rest, N m or N}, undetermined: [actuators whose effort statics does not fix], q:
the configuration they hold, settled: {joint: its value there} for the joints that settled away from
home} or {refused: why the actuators cannot}, idle {body: its
idle freedoms}, loops [{cut, kind (planar / spherical / spatial), rows, full_rows, chosen}],
rows_avoided, gruebler {kutzbach, declared}, home {joint: value}, elastic {beams: [links idealised as
beams], elastic_joints: [joints]} (the elastic elements are read and checked here too, so a malformed
or inapplicable one is refused even by a command that does not use them).

Holding at rest: the actuators hold their joints at home; what they do not drive (joints on springs,
rods spinning about their own axes) settles where the load on it vanishes (`mechkit.settling`), and
the efforts are those that hold that configuration. A floating root, a load nothing balances and a pose where the
inputs do not determine the motion are refused, each by name.

`dof_gruebler` is the loop-by-loop Kutzbach count of the topology (`mechkit.core.structure`); a
registered mechanism's declared count (its spec) is shown beside it: the two differ only where the
declared count is a modified one with overconstraints found by screw theory at a configuration (the
deployable 9RR-12URU: 6 from topology, 7 declared with one redundant constraint).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechkit import core
from mechkit.base.exceptions import MechkitError, SingularConfiguration
from mechkit.mechanism import Mechanism
from mechkit.settling import SETTLED, outside_range, settle

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
            checks["acceleration_constraint"] = _scaled(
                J @ a + gamma, np.max(np.abs(J @ a), initial=0.0), np.max(np.abs(gamma), initial=0.0)
            )
    if a is None:
        a = attempt("forward_dynamics", lambda: m.forward_dynamics(q, v, np.zeros(m.model.nv), "kkt").a)
    tau0 = np.zeros(m.model.nv)
    both = attempt(
        "kkt_vs_proximal",
        lambda: (m.forward_dynamics(q, v, tau0, "proximal").a, m.forward_dynamics(q, v, tau0, "kkt").a),
    )
    if both is not None:
        checks["kkt_vs_proximal"] = _relative(*both)
    if a is not None:
        back = attempt(
            "inverse_forward_roundtrip",
            lambda: m.forward_dynamics(q, v, m.generalized_forces(m.inverse_dynamics(q, v, a).efforts), "kkt").a,
        )
        if back is not None:
            checks["inverse_forward_roundtrip"] = _relative(back, a)
    return checks | ({} if m.spec.self_checks is None else m.spec.self_checks(m)), refused


def _plain(values: dict[str, Any]) -> dict[str, float | list[float]]:
    """Joint values as JSON numbers: a float, or a list for a joint of several coordinates."""
    return {j: float(v) if np.ndim(v) == 0 else [float(x) for x in np.ravel(v)] for j, v in values.items()}


def _weakest_motion(m: Mechanism, q: np.ndarray) -> str:
    """The joints the passive block's weakest determined motion at q turns most, and its singular value."""
    basis = m.closure_model.unactuated
    _, s, vt = np.linalg.svd(m.closure_jacobian(q) @ basis)
    k = min(len(s), m.independent_rows) - 1
    v = basis @ vt[k]
    size = {
        m.model.names[j]: float(np.linalg.norm(v[m.model.joints[j].idx_v : m.model.joints[j].idx_v + m.model.nvs[j]]))
        for j in range(1, m.model.njoints)
    }
    top = sorted((n for n, x in size.items() if x > 0.1 * max(size.values())), key=lambda n: -size[n])
    return f"the weakest passive motion (singular value {s[k]:.2e}) turns {', '.join(top)}"


def holding(m: Mechanism) -> dict[str, Any]:
    """The actuator efforts that hold the mechanism still under gravity and its springs, the actuators at
    home and the motions they do not drive settled (`mechkit.settling.settle`), or why they cannot:
    unactuated, a floating root, a load that does not settle, a pose where the inputs do not determine
    the motion.

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
    roots = [
        j
        for j in range(1, model.njoints)
        if model.parents[j] == 0 and model.joints[j].shortname() == "JointModelFreeFlyer"
    ]
    if roots:
        body = core.body_name(model, roots[0])
        return {
            "refused": f"floating root {model.names[roots[0]]!r}: nothing holds its weight (fix its body: --fix {body})"
        }
    zero = np.zeros(model.nv)
    try:
        q = settle(m, m.home_q)
    except MechkitError as err:
        return {"refused": str(err)}
    stop = outside_range(m, q, m.home_q)
    if stop:
        return {
            "refused": f"the joints no actuator drives settle against a stop: {stop} (mechkit does not model "
            "joint stops)"
        }
    try:
        result = m.inverse_dynamics(q, zero, zero)
    except SingularConfiguration as err:
        return {"refused": f"{err}: {_weakest_motion(m, q)}"}
    except MechkitError as err:
        return {"refused": str(err)}
    home, there = m.joint_values(m.home_q), _plain(m.joint_values(q))
    settled = {j: v for j, v in there.items() if np.max(np.abs(np.subtract(v, home[j]))) > SETTLED}
    return {
        "efforts": result.efforts,
        "undetermined": [a for a in m.actuated if not result.efforts_determinate[a]],
        "q": [float(x) for x in q],
        "settled": settled,
    }


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
        "closures": [
            {"name": c.closure.name, "kind": c.closure.kind, "rows": c.size, "row_set": c.closure.rows} for c in m.cuts
        ],
        "dof": mob.dof,
        "dof_gruebler": m.structure.kutzbach,
        "redundant_constraints": mob.redundant,
        "idle": dict(m.idle),
        "loops": [
            {"cut": lp.cut, "kind": lp.kind, "rows": lp.rows, "full_rows": lp.full_rows, "chosen": lp.chosen}
            for lp in m.structure.loops
        ],
        "rows_avoided": m.structure.rows_avoided,
        "gruebler": {"kutzbach": m.structure.kutzbach, "declared": declared},
        "home": _plain(m.joint_values(m.home_q)),
        "parameters": [{k: v for k, v in row.items() if k != "positive"} for row in m.params.describe()],
        "home_q": [float(x) for x in m.home_q],
        "checks": checks,
        "refused": refused,
        "holding": holding(m),
        "elastic": elastic_elements(m),
    }


def elastic_elements(m: Mechanism) -> dict[str, list[str]]:
    """The mechanism's elastic elements, read and idealised (`mechkit.elastic`).

    Args:
        m: the mechanism.

    Returns:
        {"beams": links idealised as beams, "elastic_joints": joints with an elasticity}.

    Raises:
        MalformedDescription: a malformed `<mechkit:beam>` or `<mechkit:elastic_joint>`.
        InvalidParameters: a section on a body the idealisation keeps rigid, elasticity naming a joint the
            mechanism lacks.
    """
    from mechkit.elastic import ElasticModel

    e = ElasticModel(m)
    return {"beams": [b.link for b in e.idealisation.elastic], "elastic_joints": sorted(e.data.joints)}


def format_report(r: dict[str, Any]) -> str:
    """Human-readable text of a report.

    Args:
        r: a report.

    Returns:
        The text, lines joined.
    """
    lines = [
        f"{r['name']}: {r['summary']}",
        f"  nq {r['nq']}, nv {r['nv']}, actuated: {', '.join(r['actuated']) or 'none (unactuated)'}",
        "  closures: "
        + ", ".join(f"{c['name']} ({c['kind']}, {c['rows']} {c['row_set']} rows)" for c in r["closures"]),
        f"  DOF numerical {r['dof']}, Gruebler {r['dof_gruebler']}, redundant constraints {r['redundant_constraints']}"
        + (
            f" (declared Gruebler {r['gruebler']['declared']})"
            if r["gruebler"]["declared"] not in (None, r["dof_gruebler"])
            else ""
        ),
        "  idle freedoms: " + (", ".join(f"{j} {n}" for j, n in r["idle"].items()) or "none"),
        "  loops: "
        + ", ".join(
            f"{lp['cut']} {lp['kind']} {lp['rows']}/{lp['full_rows']} rows ({lp['chosen']})" for lp in r["loops"]
        )
        + f"; {r['rows_avoided']} rows avoided",
    ]
    if r["parameters"]:
        lines.append("  parameters:")
    for p in r["parameters"]:
        mark = " (ours)" if p.get("ours") else ""
        lines.append(f"    {p['name']:<18} {p['value']!s:>12} {p['unit']:<8} {p['doc']}{mark}")
    elastic = r["elastic"]
    if elastic["beams"] or elastic["elastic_joints"]:
        lines.append(
            f"  elastic: {len(elastic['beams'])} beam(s), {len(elastic['elastic_joints'])} elastic joint(s) "
            "(`mechkit stiffness`, `mechkit modes`)"
        )
    lines.append("  self-checks (worst residual or relative error):")
    for name, value in r["checks"].items():
        lines.append(f"    {name:<32} {value:.3e}")
    for name, why in r["refused"].items():
        lines.append(f"    {name:<32} refused: {why}")
    held = r["holding"]
    lines.append(
        "  holding gravity at rest: "
        + (
            ", ".join(f"{j} {u:.6g}" for j, u in held["efforts"].items())
            if "efforts" in held
            else f"the actuators cannot ({held['refused']})"
        )
    )
    if held.get("undetermined"):
        lines.append("    not fixed by statics (least-norm shares): " + ", ".join(held["undetermined"]))
    if held.get("settled"):
        lines.append(
            "    with the undriven joints settled at: "
            + ", ".join(f"{j} {np.array2string(np.asarray(v), precision=6)}" for j, v in held["settled"].items())
        )
    return "\n".join(lines)
