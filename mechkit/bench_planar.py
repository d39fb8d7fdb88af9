"""Built-in bench methods and references for the calibration linkages four_bar and five_bar.

The core's four_bar / five_bar modules carry no `BENCH_METHODS`; their independent methods live in
`mechkit.validation` (numpy only) and are wired here in the `mechkit.bench` protocol:

- reference: closed-form kinematics and planar Newton-Euler (`validation.planar_linkages`);
- assembly: the closed form (circle intersection);
- forward dynamics: Lagrange's equations of the first kind in reference-point coordinates
  (`validation.lagrange.Linkage`: M, C_q, gamma, Q), the efforts on the motor pins;
- inverse dynamics: planar Newton-Euler, sequential SOC virtual work (`validation.planar_soc.soc_skcs`:
  the dyad at the cut first, then single links), classic virtual work over the URDF coordinates
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
from mechkit.validation.planar_soc import soc_skcs, whole_skc
from mechkit.validation.soc import classic_virtual_work, solve_soc

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
def classic(mech, sample) -> dict[str, Any]:
    return {"efforts": classic_virtual_work(whole_skc(state(mech, sample)))}


# ---------------------------------------------------------------- sequential SOC
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
