"""`mechkit simulate`: a mechanism moving in time under its forces, prescribed inputs or given torques;
the energy balance and the closure residual printed, Parquet or CSV, a plot and an animation."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from mechkit.base.atomic import resolve_output
from mechkit.base.exceptions import InvalidParameters
from mechkit.cli.common import add_mechanism_arguments, examples, load_mechanism
from mechkit.cli.progress import ProgressBars

#: Simulations of at least this many simulated seconds show a progress bar (stderr, on a terminal).
LONG_RUN = 1.0
#: Ticks of the progress bar.
TICKS = 1000


def _vector(text: str | None, what: str) -> tuple[float, ...] | None:
    if text is None:
        return None
    try:
        return tuple(float(x) for x in text.split(","))
    except ValueError:
        raise InvalidParameters(what, text, "expected numbers separated by commas") from None


def _elements(mech, args: argparse.Namespace) -> list:
    """The force elements the command line adds: reaction friction on every revolute joint, gravity, springs."""
    from mechkit import forces
    from mechkit.core import JointSpring

    out = []
    friction = _vector(args.friction, "--friction")
    if friction is not None:
        if len(friction) != 2:
            raise InvalidParameters("--friction", args.friction, "expected MU,RADIUS (RADIUS in m)")
        cm = mech.closure_model
        revolute = [
            j
            for j in cm.joint_names[: mech.model.njoints - 1]
            if mech.model.joints[mech.joint_id(j)].shortname().startswith(("JointModelR", "JointModelRevolute"))
            and mech.model.joints[mech.joint_id(j)].nv == 1
        ]
        revolute += [c.name for c in cm.closures if c.kind == "revolute"]
        spec = forces.PinFriction(friction[0], friction[1])
        out.append(forces.ReactionFriction(mech.model, cm.joint_names, cm.kernel.cuts, {j: spec for j in revolute}))
    gravity = _vector(args.gravity, "--gravity")
    if gravity is not None:
        out.append(forces.Gravity(mech.model, gravity))
    springs = []
    for item in args.spring or []:
        joint, _, values = item.partition("=")
        numbers = _vector(values, "--spring") or ()
        if len(numbers) not in (2, 3):
            raise InvalidParameters("--spring", item, "expected JOINT=STIFFNESS,REFERENCE[,DAMPING]")
        springs.append(
            JointSpring(joint.strip(), numbers[0], numbers[1], 0.0, numbers[2] if len(numbers) == 3 else 0.0)
        )
    if springs:
        out.append(forces.JointSprings(mech.model, springs, "added springs"))
    return out


def run(args: argparse.Namespace) -> None:
    """Simulate, print the summary, write what was asked.

    Args:
        args: the parsed command line.

    Raises:
        InvalidParameters: a duration not above 0 s, an output that is neither .parquet nor .csv.
    """
    from mechkit import motion, simulation
    from mechkit.simulation.plot import write_plot

    mech = load_mechanism(args)
    if not args.duration > 0:
        raise InvalidParameters("--duration", args.duration, "must be > 0 s")
    inputs = torques = None
    if args.inputs:
        inputs = motion.from_csv(mech, args.inputs)
    elif args.law:
        law = motion.from_law(mech, args.law)
        keep = [k for k, n in enumerate(law.names) if n in mech.actuated]
        inputs = motion.from_arrays(
            mech,
            law.t,
            law.values[:, keep],
            law.rates[:, keep],
            law.accelerations[:, keep],
            names=[law.names[k] for k in keep],
            source=f"{law.source} (actuated joints)",
        )
    elif args.torques:
        torques = motion.from_csv(mech, args.torques)
    if args.output and not args.output.endswith((".parquet", ".csv")):
        raise InvalidParameters("-o", args.output, "write .parquet or .csv")
    for path in (args.output, args.plot, args.animate):
        if path:
            resolve_output(path)
    latches = []
    for item in args.latch or []:
        joint, _, value = item.partition("=")
        latches.append(simulation.Latch(joint.strip(), float(value)))
    source = Path(args.name) if Path(args.name).suffix in (".xml", ".mjcf") else None
    bars = ProgressBars(None if args.duration >= LONG_RUN else False)
    result = simulation.simulate(
        mech,
        args.duration,
        inputs=inputs,
        torques=torques,
        forces=_elements(mech, args),
        source=source,
        dt=args.dt,
        rtol=args.rtol,
        atol=args.rtol * 1e-2,
        method=args.method,
        dynamics=args.dynamics,
        restitution=args.restitution,
        latches=latches,
        progress=lambda done, total: bars(f"{mech.spec.name} simulate", round(TICKS * done / total), TICKS),
    )
    print(f"{mech.spec.name}: {result.motion.source}")
    print("\n".join(result.summary()))
    for name in result.motion.effort_names:
        u = result.motion.effort(name)
        print(
            f"effort {name}: {math.nan if u.size == 0 else float(min(u, default=math.nan)):.4g} .. "
            f"{float(max(u, default=math.nan)):.4g} (N m or N)"
        )
    if args.output:
        writer = simulation.write_parquet if args.output.endswith(".parquet") else simulation.write_csv
        print(f"wrote {writer(result, args.output)}")
    if args.plot:
        print(f"wrote {write_plot(result, args.plot)}")
    if args.animate:
        from mechkit.base.atomic import write_text
        from mechkit.viz.meshcat_page import StaticScene
        from mechkit.viz.pages import compose

        scene = StaticScene()
        compose(scene, mech, list(result.motion.q), animate=True)
        print(
            f"wrote {write_text(args.animate, scene.html(mech.spec.name, f'{mech.spec.name}: {result.motion.source}'))}"
        )


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register `simulate`.

    Args:
        sub: the command line's sub-parsers.
    """
    p = sub.add_parser(
        "simulate",
        help="motion in time under forces, prescribed inputs or torques: energy balance, "
        "closure residual, Parquet/CSV, plot, animation",
        **examples(
            "mechkit simulate four_bar --duration 2 -o free.parquet --plot free.png",
            "mechkit simulate ten_bar --duration 20 --law deploy --friction 0.2,0.005 -o deploy.parquet",
        ),
    )
    add_mechanism_arguments(p)
    p.add_argument("--duration", type=float, required=True, metavar="T", help="simulated time (s)")
    drive = p.add_mutually_exclusive_group()
    drive.add_argument(
        "--inputs",
        metavar="LAW.csv",
        help="prescribed joints: CSV of t (s) and one column per joint "
        "(rad or m; optional <joint>_dot, <joint>_ddot); their efforts are recorded",
    )
    drive.add_argument(
        "--law", metavar="NAME", help="a motion law the mechanism declares, its actuated joints prescribed"
    )
    drive.add_argument(
        "--torques", metavar="LAW.csv", help="given efforts: CSV of t (s) and one column per actuator (N m or N)"
    )
    step = p.add_mutually_exclusive_group()
    step.add_argument("--dt", type=float, help="fixed step (s)")
    step.add_argument(
        "--rtol",
        type=float,
        default=1e-9,
        help="relative tolerance of the adaptive steps (default 1e-9; absolute: 1e-2 of it)",
    )
    p.add_argument(
        "--dynamics",
        choices=("proximal", "lcaba", "kkt", "nullspace"),
        help="the core's forward dynamics (default: proximal, kkt with --friction)",
    )
    p.add_argument("--method", default="RK45", help="scipy one-step method: RK45 (default), DOP853, RK23, Radau")
    p.add_argument(
        "--friction",
        metavar="MU,RADIUS",
        help="friction from the reactions on every revolute joint "
        "(cut joints included): coefficient and pin radius (m)",
    )
    p.add_argument("--gravity", metavar="GX,GY,GZ", help="gravity (m/s^2, world) instead of the model's")
    p.add_argument(
        "--spring",
        action="append",
        metavar="JOINT=K,REF[,DAMPING]",
        help="a joint spring: stiffness (N m/rad or N/m), reference (rad or m), damping (repeatable)",
    )
    p.add_argument(
        "--restitution", type=float, default=0.0, help="at the file's joint limits: 0 stop (default) .. 1 bounce"
    )
    p.add_argument(
        "--latch", action="append", metavar="JOINT=VALUE", help="a joint that locks at a value (rad or m; repeatable)"
    )
    p.add_argument("-o", "--output", help="write the table: .parquet or .csv")
    p.add_argument("--plot", help="write a plot of joints, energies and closure residual (.png, .svg, .pdf)")
    p.add_argument("--animate", metavar="OUT.html", help="write a meshcat animation (self-contained HTML)")
    p.set_defaults(func=run)
