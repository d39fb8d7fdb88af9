"""Per-step cost of the 9RR-12URU composite (66 coordinates, 60 rows) against the small mechanisms.

One run, printed: microseconds per step of the warm-started closure solve, constrained forward
dynamics (`pin.constraintDynamics` on the proximal path, and the dense KKT on the independent rows),
constrained inverse dynamics (with and without the determinacy test), plain ABA / RNEA for scale;
ratios to four_bar and five_bar measured in the same run, and the accuracy of each forward-dynamics
route against the motion's accelerations (tau from the constrained RNEA) and its closure
acceleration residual |J a + gamma|. BLAS is limited to one thread (2 shared cores).
Usage: python tools/deployable_bench.py [--budget 0.5]
"""

from __future__ import annotations

import argparse
import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")  # small dense solves on 2 shared cores: threads only contend

import itertools

import numpy as np
import pinocchio as pin

from mechkit.bench import time_per_call
from mechkit.loading import load
from mechkit.mechanism import Mechanism
from mechkit.mechanisms.truss.fold import fold

NAMES = ("four_bar", "five_bar", "tetra_3rr3uru", "deployable_9rr12uru")


def _trajectory(mech: Mechanism, steps: int) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """(q, v, a) along a motion: the paper's fold for the trusses, small input sweeps otherwise."""
    if mech.spec.name in ("tetra_3rr3uru", "deployable_9rr12uru"):
        return [(s.q, s.v, s.a) for s in fold(mech, np.linspace(0.0, 200.0, steps))]
    out, q = [], mech.home_q
    for k in range(steps):
        inputs = {j: q[mech.q_index(j)] + 0.01 for j in mech.actuated}
        q = mech.assemble(inputs, guess=q)
        rates = {j: 0.5 for j in mech.actuated}
        v = mech.velocities(q, rates)
        out.append((q, v, mech.accelerations(q, v, {j: 0.3 for j in mech.actuated})))
    return out


def _us(fn, items, budget: float) -> float:
    return float(np.median(time_per_call(fn, items, budget_s=budget, repeats=5)) * 1e6)


def measure(name: str, budget: float, steps: int = 12) -> dict[str, float]:
    """Microseconds per call of each method on one mechanism, and forward-dynamics errors."""
    mech = load(name)
    traj = _trajectory(mech, steps)
    taus = []
    for q, v, a in traj:
        tau = np.zeros(mech.model.nv)
        for joint, u in mech.inverse_dynamics(q, v, a, determinacy=False).efforts.items():
            tau[mech.v_index(joint)] = u
        taus.append(tau)
    # closure solve from the previous step advanced by v dt (what the fold scene does)
    warm = []
    for (q0, v0, _), (q1, _, _) in itertools.pairwise(traj):
        dt = 200.0 / (steps - 1) if name in ("tetra_3rr3uru", "deployable_9rr12uru") else 0.02
        guess = pin.integrate(mech.model, q0, v0 * dt)
        for j in mech.actuated:
            guess[mech.q_index(j)] = q1[mech.q_index(j)]
        warm.append(guess)
    data = mech.model.createData()
    items = list(range(len(traj)))
    out = {
        "closure solve (warm)": _us(lambda i: mech.solve_closure(warm[i % len(warm)], mech.actuated),
                                    items, budget),
        "aba (tree)": _us(lambda i: pin.aba(mech.model, data, traj[i][0], traj[i][1], taus[i]), items, budget),
        "rnea (tree)": _us(lambda i: pin.rnea(mech.model, data, *traj[i]), items, budget),
        "constraintDynamics (proximal)": _us(lambda i: mech.forward_dynamics(traj[i][0], traj[i][1], taus[i]), items, budget),
        "dense KKT (independent rows)": _us(lambda i: mech.forward_dynamics(traj[i][0], traj[i][1], taus[i], method="kkt"),
                                            items, budget),
        "constrained RNEA": _us(lambda i: mech.inverse_dynamics(*traj[i], determinacy=False), items, budget),
        "constrained RNEA + determinacy": _us(lambda i: mech.inverse_dynamics(*traj[i]), items, budget),
    }
    out["max |a| (fold)"] = max(np.abs(a).max() for _, _, a in traj)
    for method in ("proximal", "kkt"):
        err = closure = 0.0
        for (q, v, a), tau in zip(traj, taus):
            found = mech.forward_dynamics(q, v, tau, method=method).a
            err = max(err, np.abs(found - a).max())
            closure = max(closure, np.abs(mech.closure_jacobian(q) @ found + mech.closure_drift(q, v)).max())
        out[f"error a {method}"], out[f"|J a + gamma| {method}"] = err, closure
    out["nv"], out["rows"] = mech.model.nv, mech.closure_model.kernel.size
    out["iterations (warm)"] = float(np.mean([mech.solve_closure(g, mech.actuated).iterations for g in warm]))
    return out


def main(budget: float = 0.5) -> dict[str, dict[str, float]]:
    results = {name: measure(name, budget) for name in NAMES}
    extras = ("nv", "rows", "iterations (warm)", "max |a| (fold)", "error a proximal", "error a kkt",
              "|J a + gamma| proximal", "|J a + gamma| kkt")
    methods = [k for k in results[NAMES[-1]] if k not in extras]
    print("us per step (median of 5 rounds, one run, gc off; 2 shared cores)")
    print(f"{'method':32s}" + "".join(f"{n:>22s}" for n in NAMES) + f"{'deployable/four_bar':>21s}{'deployable/five_bar':>21s}")
    for m in methods:
        row = "".join(f"{results[n][m]:22.1f}" for n in NAMES)
        d = results["deployable_9rr12uru"][m]
        print(f"{m:32s}{row}{d / results['four_bar'][m]:21.1f}{d / results['five_bar'][m]:21.1f}")
    print("accuracy of forward dynamics under the constrained-RNEA efforts (rad/s^2, max over the steps)")
    for k in extras:
        print(f"{k:32s}" + "".join(f"{results[n][k]:22.3g}" for n in NAMES))
    d = results["deployable_9rr12uru"]
    print(f"deployable: constraintDynamics / dense KKT = {d['constraintDynamics (proximal)'] / d['dense KKT (independent rows)']:.2f}")
    return results


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--budget", type=float, default=0.5, help="seconds of timing per method and mechanism")
    main(parser.parse_args().budget)
