"""Built-in bench methods and references for the calibration linkages four_bar and five_bar.

The core's four_bar / five_bar modules carry no `BENCH_METHODS`; their independent methods live in
`mechkit.validation` (numpy only) and are wired here in the `mechkit.bench` protocol:

- reference: closed-form kinematics and planar Newton-Euler (`validation.planar_linkages`);
- assembly: the closed form (circle intersection);
- forward dynamics: Lagrange's equations of the first kind in reference-point coordinates
  (`validation.lagrange.Linkage`: M, C_q, gamma, Q), the efforts on the motor pins;
- inverse dynamics: planar Newton-Euler, sequential SOC virtual work (`soc_skcs`: the dyad at the
  cut first, then single links), classic virtual work over the URDF coordinates
  (`validation.soc.classic_virtual_work`, efforts only) and Lagrange's equations of the first kind
  in reference-point coordinates (`validation.lagrange`, the ten-bar patent's A f = P).

The numpy methods start from the link motion (the closed-form `LinkageState` of the sample, cached
in `sample.extra`), not from (q, v, a): their times exclude that conversion.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechkit.validation import lagrange
from mechkit.validation import planar_linkages as ref
from mechkit.validation.soc import BodyLoad, SKCInstant, WrenchSite, classic_virtual_work, solve_soc

PLANAR = ("four_bar", "five_bar")


def geometry(mech) -> ref.FourBarGeometry | ref.FiveBarGeometry:
    """The reference geometry from the mechanism's parameters."""
    p = mech.params
    cls = ref.FourBarGeometry if mech.spec.name == "four_bar" else ref.FiveBarGeometry
    names = [n for n in cls.__dataclass_fields__]
    return cls(**{n: getattr(p, n) for n in names})


def state(mech, sample) -> ref.LinkageState:
    """Closed-form motion at the sample's inputs, rates and accelerations (cached in sample.extra)."""
    if "planar_state" not in sample.extra:
        g = geometry(mech)
        if mech.spec.name == "four_bar":
            st = ref.four_bar(sample.inputs[0], sample.rates[0], sample.accelerations[0], g)
        else:
            st = ref.five_bar(tuple(sample.inputs), tuple(sample.rates), tuple(sample.accelerations), g)
        sample.extra["planar_state"] = st
    return sample.extra["planar_state"]


def _joint_vector(mech, st: ref.LinkageState, values: np.ndarray) -> np.ndarray:
    out = np.zeros(mech.model.nv)
    out[[mech.v_index(j) for j in st.coordinates]] = values
    return out


def closed_form_q(mech, sample) -> np.ndarray:
    """Assembly by circle intersection, as a mechkit q."""
    g = geometry(mech)
    if mech.spec.name == "four_bar":
        st = ref.four_bar(sample.inputs[0], 0.0, 0.0, g)
    else:
        st = ref.five_bar(tuple(sample.inputs), geometry=g)
    return _joint_vector(mech, st, st.q)


def closed_form_a(mech, sample) -> np.ndarray:
    return _joint_vector(mech, state(mech, sample), state(mech, sample).qdd)


def newton_euler(mech, sample) -> ref.PlanarDynamics:
    return ref.newton_euler(state(mech, sample))


# ---------------------------------------------------------------- classic virtual work
def _subtree(st: ref.LinkageState, link: str) -> list[str]:
    children = [j.child for j in st.joints if j.parent == link and j.name != "C"]
    return [link] + [d for child in children for d in _subtree(st, child)]


Chain = tuple[Any, ...]  # per virtual coordinate: None, "x" / "z" (translation) or a pivot (x, z) (rotation about -y)


def _point_jacobian(point: np.ndarray, chain: Chain) -> np.ndarray:
    """(6, n): virtual displacement and rotation of a body point for each virtual coordinate (world)."""
    jac = np.zeros((6, len(chain)))
    for j, pivot in enumerate(chain):
        if isinstance(pivot, str):
            jac["xz".index(pivot) * 2, j] = 1.0
        elif pivot is not None:
            d = point - pivot
            jac[:3, j] = ref.to_world(np.array([-d[1], d[0]]))
            jac[3:, j] = ref.AXIS
    return jac


def _body(link: ref.LinkState, chain: Chain) -> BodyLoad:
    jac = _point_jacobian(link.com, chain)
    return BodyLoad(link.name, link.bar.mass, link.bar.inertia_world(link.angle), ref.to_world(link.com_acceleration),
                    link.omega * ref.AXIS, link.alpha * ref.AXIS, jac[:3], jac[3:])


def whole_skc(st: ref.LinkageState) -> SKCInstant:
    """The whole linkage over its URDF coordinates, the cut "C" as loop rows (classic virtual work)."""
    n = len(st.coordinates)
    pivots: dict[str, list[Any]] = {name: [None] * n for name in st.links}
    for j, name in enumerate(st.coordinates):
        joint = st.joint(name)
        for link in _subtree(st, joint.child):
            pivots[link][j] = joint.point
    cut = st.joint("C")
    loop = (_point_jacobian(cut.point, pivots[cut.parent]) - _point_jacobian(cut.point, pivots[cut.child]))[[0, 2]]
    bodies = [_body(link, tuple(pivots[name])) for name, link in st.links.items()]
    motors = tuple((j.name, np.eye(n)[st.coordinates.index(j.name)]) for j in st.joints if j.actuated)
    return SKCInstant("whole", n, tuple(bodies), motors, loop_jacobian=loop)


def classic(mech, sample) -> dict[str, Any]:
    return {"efforts": classic_virtual_work(whole_skc(state(mech, sample)))}


# ---------------------------------------------------------------- sequential SOC
def soc_skcs(st: ref.LinkageState) -> list[SKCInstant]:
    """SKCs in solving order for a single-loop planar linkage cut at "C" with grounded motors.

    1. The dyad of the two links meeting at C (coupling degree 0): a grounded child-side link turns
       about its pivot carrying the other, which turns about C; otherwise the pair moves freely
       (x, z, a rotation, and the turn at C). Released: the pins joining the dyad to the rest.
    2. Each remaining link alone, from its ground pin (released, with its motor), the dyad's pins known.
    3. The parent-side link of C alone: C released. 4. A grounded child-side link alone: its pivot released.
    In-plane pin forces only (components fx, fz); motor torques are efforts.
    """
    cut = st.joint("C")
    parent_of = {j.child: j for j in st.joints if j.name != "C"}
    jp, jq = parent_of[cut.parent], parent_of[cut.child]

    def site(joint: ref.PlanarJoint, chain: Chain, sign: float) -> WrenchSite:
        return WrenchSite(joint.name, _point_jacobian(joint.point, chain), sign, (0, 2))

    def free(link: str) -> Chain:
        return ("x", "z", parent_of[link].point)

    if jq.parent is None:
        chain_p, chain_q = (jq.point, cut.point), (jq.point, None)
        released = (site(jp, chain_p, 1.0),)
    else:
        chain_p, chain_q = ("x", "z", jp.point, None), ("x", "z", jp.point, cut.point)
        released = (site(jp, chain_p, 1.0), site(jq, chain_q, 1.0))
    skcs = [SKCInstant("dyad at C", len(chain_p), (_body(st.links[cut.parent], chain_p), _body(st.links[cut.child], chain_q)),
                       released=released)]
    solved = {r.joint for r in released}
    for j in st.joints:
        if j.name == "C" or j.child in (cut.parent, cut.child):
            continue
        chain = free(j.child)
        known = tuple(site(k, chain, -1.0) for k in st.joints if k.parent == j.child and k.name in solved)
        motors = ((j.name, _point_jacobian(j.point, chain)[3:].T @ ref.AXIS),) if j.actuated else ()
        skcs.append(SKCInstant(j.child, 3, (_body(st.links[j.child], chain),), motors, (site(j, chain, 1.0),), known))
    chain = free(cut.parent)
    skcs.append(SKCInstant(cut.parent, 3, (_body(st.links[cut.parent], chain),), released=(site(cut, chain, -1.0),),
                           known=(site(jp, chain, 1.0),)))
    if jq.parent is None:
        chain = free(cut.child)
        skcs.append(SKCInstant(cut.child, 3, (_body(st.links[cut.child], chain),), released=(site(jq, chain, 1.0),),
                               known=(site(cut, chain, 1.0),)))
    return skcs


def soc(mech, sample) -> Any:
    """Sequential SOC virtual work (`validation.soc.solve_soc`): efforts and in-plane pin forces."""
    return solve_soc(soc_skcs(state(mech, sample)))


# ---------------------------------------------------------------- Lagrange first kind
def lagrange_problem(mech, sample) -> tuple[lagrange.Linkage, np.ndarray, np.ndarray, list[float]]:
    """The linkage in reference-point coordinates (x, z, phi of each COM) and its state; cached."""
    if "lagrange" not in sample.extra:
        st = state(mech, sample)
        names = list(st.links)
        bodies = [lagrange.Body(n, st.links[n].bar.mass, st.links[n].bar.inertia_planar,
                                np.array([st.links[n].bar.length / 2.0, 0.0])) for n in names]
        pins = []
        for j in st.joints:
            b = names.index(j.child)
            point_b = (st.links[j.child].bar.length if j.name == "C" else 0.0) * np.array([1.0, 0.0])
            if j.parent is None:
                pins.append(lagrange.Pin(j.name, None, j.point, b, point_b))
            else:
                pins.append(lagrange.Pin(j.name, names.index(j.parent), np.array([st.links[j.parent].bar.length, 0.0]), b, point_b))
        motors = [j.name for j in st.joints if j.actuated]
        linkage = lagrange.Linkage(bodies, pins, motors)
        q = np.concatenate([[*st.links[n].com, st.links[n].angle] for n in names])
        qd = np.concatenate([[*st.links[n].com_velocity, st.links[n].omega] for n in names])
        acc = [st.links[m].alpha for m in motors]  # grounded motors: relative = absolute
        sample.extra["lagrange"] = (linkage, q, qd, acc)
    return sample.extra["lagrange"]


def lagrange_first_kind(mech, sample) -> dict[str, Any]:
    """Efforts and pin forces (in-plane) from the patent's A f = P."""
    linkage, q, qd, acc = lagrange_problem(mech, sample)
    sol = linkage.solve(q, qd, acc)
    reactions = {}
    for name, f in sol.forces.items():
        reactions[name] = np.array([f[0], 0.0, f[1], 0.0, 0.0, 0.0])
    return {"efforts": sol.efforts, "reactions": reactions}


def lagrange_forward(mech, sample) -> np.ndarray:
    """Forward dynamics in reference-point coordinates: [M, C_q^T; C_q, 0] [qdd; lambda] = [Q + S^T u; gamma].

    The efforts u are the sample's tau on the motor pins (torques about -y); returns the joint
    accelerations of mechkit's q (relative angle rates of each URDF joint).
    """
    linkage, q, qd, _ = lagrange_problem(mech, sample)
    st = state(mech, sample)
    n, m = linkage.n, 2 * len(linkage.pins)
    u = np.array([sample.tau[mech.v_index(j)] for j in linkage.motors])
    K = np.zeros((n + m, n + m))
    K[:n, :n] = np.diag(linkage.mass_diag)
    K[:n, n:] = linkage.jacobian(q).T
    K[n:, :n] = linkage.jacobian(q)
    x = np.linalg.solve(K, np.concatenate([linkage.applied(q, qd) + linkage.S.T @ u, linkage.gamma(q, qd)]))
    names = list(st.links)
    alpha = {name: x[3 * i + 2] for i, name in enumerate(names)}
    joint_acc = [alpha[j.child] - (alpha[j.parent] if j.parent else 0.0) for j in (st.joint(c) for c in st.coordinates)]
    return _joint_vector(mech, st, np.array(joint_acc))


def extras(mech) -> dict[str, Any]:
    """Methods and references for the bench protocol (empty for other mechanisms)."""
    if mech.spec.name not in PLANAR:
        return {}
    return {
        "reference": {
            "assembly": ("closed form (circle intersection)", closed_form_q),
            "forward_dynamics": ("closed-form a, tau from planar Newton-Euler", closed_form_a),
            "inverse_dynamics": ("planar Newton-Euler (numpy)", newton_euler),
        },
        "methods": {
            "assembly": [("closed form (circle intersection, numpy)", closed_form_q)],
            "forward_dynamics": [("Lagrange first kind, forward (numpy, from link motion)", lagrange_forward)],
            "inverse_dynamics": [
                ("planar Newton-Euler (numpy, from link motion)", newton_euler),
                ("classic virtual work (numpy, from link motion)", classic),
                ("sequential SOC virtual work (numpy, from link motion)", soc),
                ("Lagrange first kind (numpy, from link motion)", lagrange_first_kind),
            ],
        },
    }
