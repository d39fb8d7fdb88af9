"""Benchmark of the 2-DOF spherical platform's methods, one run, microseconds per call and ratios.

Kinematics: the paper's closed-form IK (eq. 8), its Jacobian J = -B^-1 A, and forward kinematics by
the paper's iteration, Newton on eq. (7) and the core's closure solver (each started 0.05 rad from
the answer). Dynamics: motor torques and reactions by Pinocchio's constrained RNEA
(`Mechanism.inverse_dynamics`, with and without the determinacy test) and by SOC virtual work
(efforts only: the first SKC; every joint: all SKCs). Poses: the cone scene. Writes
docs/figures/spherical_2dof_bench.png and prints the table.
Usage: python tools/spherical_2dof_bench.py [--budget 1.0]
"""

from __future__ import annotations

import argparse
from collections.abc import Callable
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from mechkit.bench import time_per_call
from mechkit.loading import load
from mechkit.mechanisms.spherical_2dof import kinematics as kin
from mechkit.mechanisms.spherical_2dof import soc
from mechkit.mechanisms.spherical_2dof.fk import solve_fk
from mechkit.mechanisms.spherical_2dof.kinematics import BRANCHES
from mechkit.mechanisms.spherical_2dof.scenes import cone_attitude, cone_times
from mechkit.mechanisms.spherical_2dof.tree import state
from mechkit.validation.soc import solve_soc

OUT = Path(__file__).resolve().parent.parent / "docs" / "figures" / "spherical_2dof_bench.png"


def _interleaved(
    cases: dict[str, list[Callable[[], object]]], budget: float, rounds: int = 7
) -> dict[str, float]:
    """Median time (us) of one call per case; the cases take turns over ``rounds`` rounds (``budget``
    s per case in all), so that every case sees the same load of the shared machine."""
    times: dict[str, list[float]] = {name: [] for name in cases}
    for _ in range(rounds):
        for name, calls in cases.items():
            times[name].append(
                time_per_call(lambda call: call(), calls, budget_s=budget / rounds, repeats=1)[0]
            )
    return {name: float(np.median(t)) * 1e6 for name, t in times.items()}


def main(budget: float = 1.0, out: Path = OUT) -> dict[str, float]:
    mech = load("spherical_2dof")
    p = mech.params
    t = cone_times(8)
    phis, rates, accs = cone_attitude(t)
    thetas = [kin.inverse_kinematics(p, phi, BRANCHES) for phi in phis]
    states = [state(mech, *x) for x in zip(phis, rates, accs)]
    efforts = [soc.solve(p, *x).efforts for x in zip(phis, rates, accs)]
    cases = {
        "IK eq. (8)": [lambda phi=phi: kin.inverse_kinematics(p, phi, BRANCHES) for phi in phis],
        "J = -B^-1 A": [lambda th=th, phi=phi: kin.jacobian(p, th, phi) for th, phi in zip(thetas, phis)],
        "FK paper": [
            lambda th=th, phi=phi: solve_fk(mech, "paper", th, phi + 0.05) for th, phi in zip(thetas, phis)
        ],
        "FK Newton": [
            lambda th=th, phi=phi: solve_fk(mech, "newton", th, phi + 0.05) for th, phi in zip(thetas, phis)
        ],
        "FK closure solver": [
            lambda th=th, phi=phi: solve_fk(mech, "closure", th, phi + 0.05) for th, phi in zip(thetas, phis)
        ],
        "ID Pinocchio": [lambda s=s: mech.inverse_dynamics(*s, determinacy=False) for s in states],
        "ID Pinocchio + determinacy": [lambda s=s: mech.inverse_dynamics(*s) for s in states],
        "ID SOC efforts+support": [lambda x=x: solve_soc(soc.skcs(p, *x)) for x in zip(phis, rates, accs)],
        "ID SOC every joint": [
            lambda x=x, u=u: solve_soc(soc.skcs(p, *x, efforts=u))
            for x, u in zip(zip(phis, rates, accs), efforts)
        ],
    }
    fk_cases = [k for k in cases if k.startswith("FK")]
    id_cases = [k for k in cases if k.startswith("ID")]
    us = _interleaved(cases, budget)

    reference = {
        name: ref
        for group, ref in (
            (["IK eq. (8)", "J = -B^-1 A"], "IK eq. (8)"),
            (fk_cases, "FK paper"),
            (id_cases, "ID Pinocchio"),
        )
        for name in group
    }
    print(f"{'method':28s} {'us/call':>9s}  ratio")
    for name, ref in reference.items():
        print(f"{name:28s} {us[name]:9.1f}  {us[name] / us[ref]:5.2f} x {ref}")

    fig, ax = plt.subplots(figsize=(10, 4.5))
    names = list(us)
    ax.barh(names, [us[n] for n in names], color=["C0"] * 2 + ["C1"] * len(fk_cases) + ["C2"] * len(id_cases))
    for k, name in enumerate(names):
        ref = reference[name]
        ax.text(
            us[name], k, f" {us[name]:.0f} us ({us[name] / us[ref]:.2f} x {ref})", va="center", fontsize=8
        )
    ax.set_xscale("log")
    ax.set_xlim(right=10 * max(us.values()))
    ax.set(
        xlabel="time per call (us, median of 7 interleaved rounds, one run, gc off; 2 shared cores)",
        title="spherical_2dof: kinematics and inverse dynamics, per method",
    )
    ax.invert_yaxis()
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    print(f"wrote {out}")
    return us


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--budget", type=float, default=1.0, help="seconds of timing per method")
    main(parser.parse_args().budget)
