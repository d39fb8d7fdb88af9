"""The design studies of docs/sweeps.md: the gimbal's linear-rule error over its geometry (r, h), the
2T1R's peak motor torque over (l1, l2) with and without its redundant limb, the ten-bar sized as the
patent's step 4 asks, and the deployable truss's rod tubes for first frequency per kilogram. Writes the
results folders under --work, the figures under docs/figures/, and prints the numbers the page quotes.

    PYTHONPATH=. python tools/sweep_showcases.py [--work /tmp/showcases] [--workers 2] \\
        [--only gimbal,2t1r,ten_bar,deployable]
"""

from __future__ import annotations

import argparse
import shutil
import time
from pathlib import Path

import numpy as np

import mechkit
from mechkit.catalog.registry import get_spec
from mechkit.sweep import DesignSpace, Study, parse_axis, read, sweep
from mechkit.sweep.optimise import optimise
from mechkit.sweep.plots import heat_map, pareto_mask, pareto_plot

FIGURES = Path(__file__).resolve().parent.parent / "docs" / "figures"


def deployment_metrics(mech: mechkit.Mechanism) -> dict[str, float]:
    """The ten-bar's declared `deployment` metric (max_motor_torque, latch_speed) of one design."""
    return next(m for m in get_spec("ten_bar").design_metrics if m.name == "deployment").fn(mech)


def _fresh(path: Path) -> Path:
    shutil.rmtree(path, ignore_errors=True)
    return path


def gimbal(work: Path, workers: int) -> None:
    space = DesignSpace((parse_axis("pivot_radius=0.8:1.2:9"), parse_axis("pivot_offset=0.55:0.85:9")))
    start = time.perf_counter()
    s = sweep("rocket_gimbal", space, _fresh(work / "gimbal"), metrics=("rule_error",), workers=workers)
    frame = read(s.out)
    ok = frame[frame["status"] == "ok"]
    best = ok.loc[ok["rule_error"].idxmin()]
    print(
        f"gimbal: {s.designs} designs in {time.perf_counter() - start:.1f} s, {s.statuses}; rule_error "
        f"{np.degrees(ok['rule_error'].min()):.3f}..{np.degrees(ok['rule_error'].max()):.3f} deg; best at "
        f"r={best['pivot_radius']:.3f} m, h={best['pivot_offset']:.3f} m: {np.degrees(best['rule_error']):.3f} deg"
    )
    frame = frame.assign(rule_error_deg=np.degrees(frame["rule_error"]))
    heat_map(
        frame,
        "pivot_radius",
        "pivot_offset",
        "rule_error_deg",
        FIGURES / "sweep_gimbal_rule_error.png",
        "gimbal: linear rule's worst error",
        "deg",
    )


def parallel(work: Path, workers: int) -> None:
    space = DesignSpace((parse_axis("l1=0.30:0.50:7"), parse_axis("l2=0.16:0.26:6")))
    study = Study(scene="motion_law", period=5.0)
    frames = {}
    for label, base in (("three motors", {}), ("four motors", {"redundant_actuation": "true"})):
        start = time.perf_counter()
        s = sweep(
            "parallel_2t1r",
            space,
            _fresh(work / f"p2t1r_{len(base)}"),
            study,
            ("peak_effort",),
            base=base,
            workers=workers,
        )
        frame = read(s.out)
        efforts = [c for c in frame.columns if c.startswith("peak_effort.")]
        frames[label] = frame.assign(peak_motor_torque=frame[efforts].max(axis=1))
        ok = frames[label][frames[label]["status"] == "ok"]
        print(
            f"2T1R {label}: {s.designs} designs in {time.perf_counter() - start:.1f} s, {s.statuses}; peak motor "
            f"torque {ok['peak_motor_torque'].min():.2f}..{ok['peak_motor_torque'].max():.2f} N m"
        )
        heat_map(
            frames[label],
            "l1",
            "l2",
            "peak_motor_torque",
            FIGURES / f"sweep_2t1r_{len(base)}.png",
            f"2T1R, {label}: peak motor torque",
            "N m",
        )
    a, b = (frames[k].set_index("index") for k in ("three motors", "four motors"))
    both = (a["status"] == "ok") & (b["status"] == "ok")
    ratio = (b["peak_motor_torque"] / a["peak_motor_torque"])[both]
    print(
        f"2T1R: four motors / three motors peak torque over {int(both.sum())} designs: "
        f"{ratio.min():.3f}..{ratio.max():.3f} (median {ratio.median():.3f})"
    )


def ten_bar(work: Path, workers: int) -> None:
    axes = ("l27=0.20:0.30", "l67=0.45:0.55", "spring_stiffness=2:6", "spring_preload=3:8")
    space = DesignSpace(tuple(parse_axis(a) for a in axes), "lhs", 24, seed=1)
    start = time.perf_counter()
    out = _fresh(work / "ten_bar")
    s = sweep("ten_bar", space, out, workers=workers, chunk_size=2)
    frame = read(out)
    print(f"ten_bar: {s.designs} designs in {time.perf_counter() - start:.1f} s, {s.statuses}")
    default = mechkit.load("ten_bar")
    d = deployment_metrics(default)
    print(f"ten_bar default: max motor torque {d['max_motor_torque']:.2f} N m, latch speed {d['latch_speed']:.2e} m/s")
    ok = frame[frame["status"] == "ok"]
    gentle = ok[ok["latch_speed"] <= d["latch_speed"]]
    pick = (gentle if not gentle.empty else ok).sort_values("max_motor_torque").iloc[0]
    print(
        f"ten_bar chosen from the sweep: {pick[list(space.names)].to_dict()} -> torque {pick['max_motor_torque']:.2f}"
        f" N m, latch {pick['latch_speed']:.2e} m/s; Pareto designs "
        f"{int(pareto_mask(ok['max_motor_torque'].to_numpy(), ok['latch_speed'].to_numpy()).sum())}"
    )
    start = time.perf_counter()
    refined = optimise(out, "max_motor_torque", starts=1, max_evaluations=24, workers=workers)[0]
    print(
        f"ten_bar refined in {time.perf_counter() - start:.1f} s: {refined.start_value:.2f} -> {refined.value:.2f} "
        f"N m at {refined.best} ({refined.evaluations} evaluations)"
    )
    chosen = mechkit.load("ten_bar", **refined.best)
    c = deployment_metrics(chosen)
    print(f"ten_bar refined design: torque {c['max_motor_torque']:.2f} N m, latch speed {c['latch_speed']:.2e} m/s")
    pareto_plot(
        frame,
        "max_motor_torque",
        "latch_speed",
        FIGURES / "sweep_ten_bar_pareto.png",
        "ten-bar: motor torque vs latch-up speed",
        {"default": (d["max_motor_torque"], d["latch_speed"]), "refined": (c["max_motor_torque"], c["latch_speed"])},
    )
    from mechkit.viz.pages import animation

    animation(chosen, "deploy", work / "ten_bar_refined.html")
    print(f"ten_bar animation: {work / 'ten_bar_refined.html'}")


def deployable_tubes(work: Path, workers: int) -> None:
    """The deployable truss's rod tubes (outer x inner diameter) for first frequency per kilogram, the rods'
    masses following their tubes (`rod_masses=tubes`)."""
    space = DesignSpace((parse_axis("tube_outer=0.014:0.030:5"), parse_axis("tube_inner=0.006:0.012:4")))
    start = time.perf_counter()
    s = sweep(
        "deployable_9rr12uru",
        space,
        _fresh(work / "deployable_tubes"),
        metrics=("mass", "first_frequency", "frequency_per_mass"),
        base={"rod_masses": "tubes"},
        workers=workers,
    )
    frame = read(s.out)
    ok = frame[frame["status"] == "ok"]
    best = ok.loc[ok["frequency_per_mass"].idxmax()]
    print(
        f"deployable tubes: {s.designs} designs in {time.perf_counter() - start:.1f} s, {s.statuses}; first frequency "
        f"{ok['first_frequency'].min():.2e}..{ok['first_frequency'].max():.2e} Hz, mass {ok['mass'].min():.2f}.."
        f"{ok['mass'].max():.2f} kg; best per kg: {best['tube_outer'] * 1e3:.0f} / {best['tube_inner'] * 1e3:.0f} mm, "
        f"{best['first_frequency']:.2e} Hz, {best['mass']:.2f} kg, {best['frequency_per_mass']:.2e} Hz/kg"
    )
    heat_map(
        frame,
        "tube_outer",
        "tube_inner",
        "frequency_per_mass",
        FIGURES / "sweep_deployable_tubes.png",
        "deployable truss: first frequency per kilogram",
        "Hz/kg",
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--work", type=Path, default=Path("/tmp/showcases"))
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--only", default="gimbal,2t1r,ten_bar,deployable")
    args = parser.parse_args()
    args.work.mkdir(parents=True, exist_ok=True)
    FIGURES.mkdir(parents=True, exist_ok=True)
    chosen = args.only.split(",")
    for key, fn in (("gimbal", gimbal), ("2t1r", parallel), ("ten_bar", ten_bar), ("deployable", deployable_tubes)):
        if key in chosen:
            fn(args.work, args.workers)


if __name__ == "__main__":
    main()
