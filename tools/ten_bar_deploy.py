"""The ten-bar deployment, stowed to deployed, with every cross-check printed (one run).

Pinocchio's constrained ABA and the patent's Lagrange first-kind method from the same parameters,
RK4 with projection; reactions by constrained RNEA, Lagrange multipliers and SOC at sampled
instants; the full closure solve against the dimension reduction along the motion; where the
methods fail (kinematic split, unstabilised drift, distance from singular poses).

Usage: python tools/ten_bar_deploy.py [--dt 0.005] [--samples 9]
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

import mechkit
from mechkit.mechanisms.ten_bar import checks as tc
from mechkit.mechanisms.ten_bar import dynamics as td
from mechkit.mechanisms.ten_bar import geometry as geo
from mechkit.mechanisms.ten_bar import lagrange_model as lm
from mechkit.mechanisms.ten_bar import limits as tl
from mechkit.mechanisms.ten_bar import params as tp


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--t-end", type=float, default=None, help="stop early (s); default: the whole deployment"
    )
    parser.add_argument("--dt", type=float, default=0.005, help="RK4 step (s)")
    parser.add_argument("--samples", type=int, default=9, help="instants for the three-way reactions")
    args = parser.parse_args()
    m = mechkit.load("ten_bar")
    p = m.params
    pin_run = td.PinocchioDeployment(m)
    motors = [td.JOINT_ORDER.index(j) for j in tp.MOTORS]
    r5 = td.JOINT_ORDER.index("R5")

    clock = time.perf_counter()
    a = td.deploy(pin_run, m.home_q, args.dt, args.t_end)
    t_pin = time.perf_counter() - clock
    clock = time.perf_counter()
    b = td.deploy(td.LagrangeJointDeployment(p), pin_run.joint_angles(m.home_q), args.dt, args.t_end)
    t_lag = time.perf_counter() - clock
    print(f"Deployment 0..{a.t[-1]:g} s (motor laws end at {p.deploy_time:g} s)")
    print(f"  RK4 dt = {args.dt * 1e3:g} ms, projection after each step")
    print(f"  final motor angles (deg): {np.degrees(a.angles[-1, motors]).round(9)} (deployed: 0, 0)")
    rocker = np.degrees(a.angles[:, r5])
    print(
        f"  rocker R5 (deg): stowed {rocker[0]:.2f}, range [{rocker.min():.2f}, {rocker.max():.2f}], "
        f"final {rocker[-1]:.2f}"
    )
    print(
        f"  motor torques (N m): R1 [{a.torques[:, 0].min():.3f}, {a.torques[:, 0].max():.3f}], "
        f"R3 [{a.torques[:, 1].min():.3f}, {a.torques[:, 1].max():.3f}]"
    )
    print(f"  closure residual max (m): Pinocchio {a.residual.max():.2e}, Lagrange {b.residual.max():.2e}")
    print(
        f"  energy balance |E - W - E0| max (J): Pinocchio {a.energy_error:.2e}, "
        f"Lagrange {b.energy_error:.2e}"
    )
    print(
        f"  energy E = kinetic + gravity + spring spans {np.ptp(a.energy):.2f} J; "
        f"work of motors minus damper {a.work[-1]:.2f} J"
    )
    print(
        "  Pinocchio vs Lagrange (same step, joint coordinates): "
        f"angles {np.max(np.abs(a.angles - b.angles)):.2e} rad, "
        f"torques {np.max(np.abs(a.torques - b.torques)):.2e} N m"
    )
    print(f"  wall time: Pinocchio {t_pin:.1f} s, Lagrange {t_lag:.1f} s ({len(a.t) - 1} steps)")

    print("Lagrange in its own coordinates (x, z, phi per link) vs Pinocchio, first 0.4 s (spring release):")
    own = td.LagrangeDeployment(p)
    q_own = lm.lagrange_coordinates(p, geo.stowed_pose(p))
    previous = None
    for dt in (0.02, 0.01, 0.005):
        diff = np.max(
            np.abs(td.deploy(pin_run, m.home_q, dt, 0.4).angles - td.deploy(own, q_own, dt, 0.4).angles)
        )
        order = "" if previous is None else f", order {math.log2(previous / diff):.2f}"
        print(f"  dt = {dt * 1e3:5.1f} ms: max angle difference {diff:.2e} rad{order}")
        previous = diff

    every = max(1, (len(a.t) - 1) // (args.samples - 1))
    times, results = tc.reactions_along(m, a, every)
    worst = max(tc.reaction_disagreement({k: v[i] for k, v in results.items()}) for i in range(len(times)))
    print(f"Reactions at {len(times)} instants (2 motor torques + in-plane forces of the 12 pairs,")
    print("  R1 and R5 the wall supports):")
    print(f"  Pinocchio RNEA vs Lagrange multipliers vs SOC, worst relative difference {worst:.2e}")
    peak = max(np.max(np.abs(r.vector())) for r in results["pinocchio"])
    print(f"  largest value {peak:.2f} (N or N m)")

    inputs = [{"R1": x[motors[0]], "R3": x[motors[1]], "R5": x[r5]} for x in a.angles[::20]]
    kin = tc.kinematics_disagreement(m, inputs)
    print(
        f"Kinematics along the deployment ({len(inputs)} instants): full closure vs dimension reduction "
        f"{kin['full_vs_reduction']:.2e} rad, vs closed form {kin['full_vs_closed_form']:.2e} rad"
    )

    split = tl.kinematic_split(m, m.home_q)
    print("Where the methods fail:")
    print(
        f"  motors alone: {split.nullity} joint motion left free "
        f"(five-bar unit with R1 only: {split.five_bar_nullity}); free direction (rad/s per unit): "
        + ", ".join(f"{j} {split.direction[m.v_index(j)]:+.3f}" for j in td.JOINT_ORDER)
    )
    for label, baumgarte, project in tl.STABILISATIONS:
        run = tl.drift(m, 5.0, 0.02, baumgarte, project)
        print(f"  0..5 s at dt = 20 ms, {label:28s}: closure residual max {run.residual.max():.2e} m")
    margins = tl.loop_margins(p, a.angles[::10])
    print(
        "  distance from singular poses over the deployment (min sine of the angle at the closing hinge): "
        + ", ".join(
            f"{k} {v.min():.3f} ({math.degrees(math.asin(v.min())):.1f} deg)" for k, v in margins.items()
        )
    )


if __name__ == "__main__":
    main()
