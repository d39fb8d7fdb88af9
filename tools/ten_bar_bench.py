"""Benchmark of the ten-bar's methods, one run, printed (microseconds per call, ratios in this run).

Dynamics: per evaluation of the deployment's right-hand side (accelerations and motor torques at a
state) and per RK4 step with projection; inverse dynamics (torques and all 12 pair reactions);
kinematics: one position solve of the whole linkage by each route, tracking a moving input.

Usage: python tools/ten_bar_bench.py [--repeat N]
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import mechkit
from mechkit.bench.raw import raw_constraint_dynamics
from mechkit.mechanisms.ten_bar import checks as tc
from mechkit.mechanisms.ten_bar import dynamics as td
from mechkit.mechanisms.ten_bar import geometry as geo
from mechkit.mechanisms.ten_bar import kinematics as tk
from mechkit.mechanisms.ten_bar import params as tp
from mechkit.mechanisms.ten_bar import soc as ts


def per_call(fn, repeat: int) -> float:
    """Median over 5 batches of `repeat` calls, microseconds per call."""
    fn()
    batches = []
    for _ in range(5):
        t0 = time.perf_counter()
        for _ in range(repeat):
            fn()
        batches.append((time.perf_counter() - t0) / repeat * 1e6)
    return float(np.median(batches))


def table(title: str, rows: dict[str, float], base: str) -> None:
    print(f"\n{title} (ratio to {base!r})")
    for name, us in rows.items():
        print(f"  {name:58s} {us:10.1f} us   x{us / rows[base]:6.2f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=20)
    n = parser.parse_args().repeat
    m = mechkit.load("ten_bar")
    p = m.params
    t = 0.37 * p.deploy_time
    q = tk.full_solve(m, {"R1": 0.7, "R3": -1.2, "R5": -0.3}, m.home_q)
    v = m.velocities(q, {"R1": 0.05, "R3": -0.1, "R5": 0.2}, inputs=("R1", "R3", "R5"))
    pin_run, pin_kkt = td.PinocchioDeployment(m), td.PinocchioDeployment(m, method="kkt")
    lag_own, lag_joint = td.LagrangeDeployment(p), td.LagrangeJointDeployment(p)
    qL, vL = td.lagrange_state(p, q, v, m)
    qj, vj = pin_run.joint_angles(q), v[[m.v_index(j) for j in td.JOINT_ORDER]]
    tau = np.zeros(m.model.nv)
    raw = raw_constraint_dynamics(m)
    L = lag_own.L
    acc = tp.motor_law(p, t)[2]

    table(
        "Dynamics: one evaluation at a state",
        {
            "pin.constraintDynamics (raw call)": per_call(
                lambda: raw(q, v, tau), n
            ),
            "Mechanism.forward_dynamics proximal (1 call)": per_call(
                lambda: m.forward_dynamics(q, v, tau), n
            ),
            "Mechanism.forward_dynamics kkt (1 call)": per_call(
                lambda: m.forward_dynamics(q, v, tau, method="kkt"), n
            ),
            "Pinocchio rhs, prescribed motors (3 constrained ABA)": per_call(lambda: pin_run.rhs(t, q, v), n),
            "Pinocchio rhs, prescribed motors (3 dense KKT)": per_call(lambda: pin_kkt.rhs(t, q, v), n),
            "Lagrange first kind A f = P (numpy, own coordinates)": per_call(lambda: L.solve(qL, vL, acc), n),
            "Lagrange rhs in joint coordinates (FK + A f = P)": per_call(lambda: lag_joint.rhs(t, qj, vj), n),
        },
        "pin.constraintDynamics (raw call)",
    )

    def step(system, q0, v0, dt=0.005):
        return lambda: td.integrate(system, q0, v0, t + dt, dt, t0=t)

    table(
        "Dynamics: one RK4 step with projection (dt = 5 ms, incl. recording)",
        {
            "Pinocchio constrained ABA": per_call(step(pin_run, q, v), max(1, n // 4)),
            "Lagrange, own coordinates": per_call(step(lag_own, qL, vL), max(1, n // 4)),
            "Lagrange, joint coordinates": per_call(step(lag_joint, qj, vj), max(1, n // 4)),
        },
        "Pinocchio constrained ABA",
    )

    a, _, _ = pin_run.rhs(t, q, v)
    fext = tc.spring_fext(m, pin_run, q, v)
    sol = L.solve(qL, vL, acc)
    table(
        "Inverse dynamics: motor torques and all 12 pair reactions",
        {
            "Mechanism.inverse_dynamics (constrained RNEA, determinacy)": per_call(
                lambda: m.inverse_dynamics(q, v, a, fext), n
            ),
            "Mechanism.inverse_dynamics (no determinacy test)": per_call(
                lambda: m.inverse_dynamics(q, v, a, fext, determinacy=False), n
            ),
            "Lagrange multipliers (A f = P)": per_call(lambda: L.solve(qL, vL, acc), n),
            "SOC virtual work (9 SKCs)": per_call(lambda: ts.solve(L, qL, vL, sol.qdd), n),
        },
        "Mechanism.inverse_dynamics (no determinacy test)",
    )

    reduction = tk.DimensionReduction(m)
    guess = {j: q[m.q_index(j)] for j in td.JOINT_ORDER}
    nudged = {"R1": 0.7 + 1e-3, "R3": -1.2 + 1e-3, "R5": -0.3 + 1e-3}  # the next instant of a tracked path
    table(
        "Kinematics: one position solve, from the previous instant",
        {
            "full closure (core Gauss-Newton, 6 rows, 6 unknowns)": per_call(
                lambda: tk.full_solve(m, nudged, q), n
            ),
            "dimension reduction (3 reduced Pinocchio units)": per_call(
                lambda: reduction.solve(nudged, guess), n
            ),
            "closed form (circle intersections, numpy)": per_call(
                lambda: geo.pose(p, nudged["R1"], nudged["R3"], nudged["R5"]), n
            ),
        },
        "full closure (core Gauss-Newton, 6 rows, 6 unknowns)",
    )


if __name__ == "__main__":
    main()
