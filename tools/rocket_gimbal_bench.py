"""Benchmark of the engine gimbal's methods, one run: microseconds per call and ratios.

Kinematics: closed-form IK; FK by the paper's resultant (eliminant, roots, common-root test, polish,
in-range pick), by Newton from the null pose, and by the core's closure solver (`Mechanism.assemble`
from neutral). Dynamics over the swing scene: actuator forces and every joint's reaction by
Pinocchio's constrained RNEA (`Mechanism.inverse_dynamics`, thrust as fext, with and without the
determinacy test) and by SOC virtual work (analytic motion + SKCs + solve). Writes
docs/figures/rocket_gimbal_bench.png and prints the table.
Usage: python tools/rocket_gimbal_bench.py [--budget 1.0]
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
from mechkit.mechanisms.rocket_gimbal.checks import fk_closure
from mechkit.mechanisms.rocket_gimbal.kinematics import actuator_lengths, fk_newton
from mechkit.mechanisms.rocket_gimbal.params import geometry
from mechkit.mechanisms.rocket_gimbal.resultant import fk_resultant, pick_in_range
from mechkit.mechanisms.rocket_gimbal.scenes import SwingScene, thrust_fext
from mechkit.mechanisms.rocket_gimbal.soc import soc_skcs
from mechkit.mechanisms.rocket_gimbal.state import joint_state
from mechkit.validation.soc import solve_soc

OUT = Path(__file__).resolve().parent.parent / "docs" / "figures" / "rocket_gimbal_bench.png"


def _time(calls: list[Callable[[], object]], budget_s: float) -> float:
    """Median time (us) of one call over 5 repeats, cycling through ``calls`` (`mechkit.bench` timer)."""
    return float(np.median(time_per_call(lambda call: call(), calls, budget_s, 5)) * 1e6)


def main(budget_s: float = 1.0, out: Path = OUT) -> dict[str, float]:
    mech = load("rocket_gimbal")
    p, geo, scene = mech.params, geometry(mech.params), SwingScene()
    rng = np.random.default_rng(0)
    stroke_set = rng.uniform(-0.11, 0.11, size=(16, 2))
    angle_set = [fk_newton(geo, s) for s in stroke_set]
    times = np.linspace(0.0, 1.0, 16, endpoint=False)
    states = [(scene.motion(p, t), *joint_state(mech, scene.motion(p, t))) for t in times]
    fexts = [thrust_fext(mech, q, scene) for _, q, _, _ in states]

    timings = {
        "IK closed form": _time([lambda x=x: actuator_lengths(geo, *x) for x in angle_set], budget_s),
        "FK resultant (paper)": _time(
            [lambda s=s: pick_in_range(fk_resultant(geo, s)) for s in stroke_set], budget_s
        ),
        "FK Newton": _time([lambda s=s: fk_newton(geo, s) for s in stroke_set], budget_s),
        "FK closure solver": _time([lambda s=s: fk_closure(mech, s) for s in stroke_set], budget_s),
        "ID Pinocchio (+determinacy)": _time(
            [lambda s=s, f=f: mech.inverse_dynamics(*s[1:], fext=f) for s, f in zip(states, fexts)], budget_s
        ),
        "ID Pinocchio (no determinacy)": _time(
            [
                lambda s=s, f=f: mech.inverse_dynamics(*s[1:], fext=f, determinacy=False)
                for s, f in zip(states, fexts)
            ],
            budget_s,
        ),
        "ID SOC (motion + SKCs + solve)": _time(
            [lambda t=t: solve_soc(soc_skcs(p, scene.motion(p, t), scene)) for t in times], budget_s
        ),
    }
    ratios = {
        "FK resultant / Newton": timings["FK resultant (paper)"] / timings["FK Newton"],
        "FK closure solver / Newton": timings["FK closure solver"] / timings["FK Newton"],
        "ID SOC / Pinocchio (no determinacy)": timings["ID SOC (motion + SKCs + solve)"]
        / timings["ID Pinocchio (no determinacy)"],
        "ID Pinocchio determinacy / without": timings["ID Pinocchio (+determinacy)"]
        / timings["ID Pinocchio (no determinacy)"],
    }
    fig, ax = plt.subplots(figsize=(9, 4))
    names = list(timings)
    ax.barh(names, [timings[k] for k in names], color="C0")
    ax.set_xscale("log")
    ax.set(xlabel="time per call (us, log scale)", title="rocket_gimbal: methods, one run on this machine")
    for i, k in enumerate(names):
        ax.text(timings[k], i, f" {timings[k]:.0f}", va="center", fontsize=8)
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=90)
    plt.close(fig)
    return {**{f"{k} (us)": v for k, v in timings.items()}, **{f"ratio {k}": v for k, v in ratios.items()}}


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--budget", type=float, default=1.0, help="seconds of timing per method")
    parser.add_argument("--out", type=Path, default=OUT)
    args = parser.parse_args()
    for key, value in main(args.budget, args.out).items():
        print(f"{key:45s} {value:10.2f}")
