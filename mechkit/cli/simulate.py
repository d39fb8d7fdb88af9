"""`mechkit simulate`: a mechanism moving in time under its forces, prescribed inputs or given torques;
the energy balance and the closure residual printed, Parquet or CSV, a plot and an animation."""

from __future__ import annotations

import argparse
import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from mechkit.base.atomic import resolve_output
from mechkit.base.exceptions import InvalidArgument, InvalidParameters, MethodUnavailable
from mechkit.base.joint_arguments import joint_names
from mechkit.cli import option_values
from mechkit.cli.common import (
    add_base_arguments,
    add_mechanism_arguments,
    assembly_line,
    carried_inputs,
    check_writers,
    examples,
    load_mechanism,
)
from mechkit.cli.progress import ProgressBars

#: Simulations of at least this many simulated seconds show a progress bar (stderr, on a terminal).
LONG_RUN = 1.0
#: Ticks of the progress bar.
TICKS = 1000
#: The formats `--plot` writes (matplotlib's, those the help names).
PLOT_SUFFIXES = (".png", ".svg", ".pdf")


@dataclass(frozen=True)
class _Added:
    """What the command line adds to the run, parsed before the mechanism loads: friction (mu, pin radius m)
    on every revolute joint, gravity (m/s^2, world), springs (joint -> stiffness, reference, damping),
    latches (joint -> value, rad or m)."""

    friction: list[float] | None
    gravity: list[float] | None
    springs: dict[str, list[float]]
    latches: dict[str, list[float]]
    torques: dict[str, list[float]]
    threshold: float

    @classmethod
    def of(cls, args: argparse.Namespace) -> _Added:
        """The values of --friction, --gravity, --spring, --latch, --torque and --friction-rate
        (`mechkit.cli.option_values`)."""
        from mechkit.forces import SPEED_THRESHOLD

        rate = SPEED_THRESHOLD if args.friction_rate is None else args.friction_rate
        if not (rate > 0 and math.isfinite(rate)):
            raise InvalidArgument("--friction-rate", rate, "must be a finite rate > 0 (rad/s or m/s)")
        return cls(
            None if args.friction is None else option_values.numbers("--friction", args.friction, 2, what="MU,RADIUS"),
            None if args.gravity is None else option_values.numbers("--gravity", args.gravity, 3, what="GX,GY,GZ"),
            option_values.named_numbers("--spring", args.spring, "JOINT=STIFFNESS,REFERENCE[,DAMPING]", (2, 3)),
            option_values.named_numbers("--latch", args.latch, "JOINT=VALUE (rad or m)", 1),
            option_values.named_numbers("--torque", args.torque, "JOINT=VALUE (N m or N)", 1),
            rate,
        )

    def elements(self, mech, skip: Sequence[str] = ()) -> list:
        """The force elements: reaction friction on every revolute joint, gravity, springs (loop-cut joints'
        among them), constant efforts (a source each) on the joints `--torque` names (not those in `skip`:
        the description's tendon actuators, set by `_with_tendon_forces`)."""
        from mechkit import forces
        from mechkit.core import JointSpring

        out = []
        if self.friction is not None:
            cm = mech.closure_model
            revolute = [
                j
                for j in cm.joint_names[: mech.model.njoints - 1]
                if mech.model.joints[mech.joint_id(j)].shortname().startswith(("JointModelR", "JointModelRevolute"))
                and mech.model.joints[mech.joint_id(j)].nv == 1
            ]
            revolute += [c.name for c in cm.closures if c.kind == "revolute"]
            spec = forces.PinFriction(self.friction[0], self.friction[1], threshold=self.threshold)
            out.append(forces.ReactionFriction(mech.model, cm.joint_names, cm.kernel.cuts, {j: spec for j in revolute}))
        if self.gravity is not None:
            out.append(forces.Gravity(mech.model, self.gravity))
        cuts = mech.closure_model.kernel.cuts
        cut_names = {c.closure.name for c in cuts}
        springs = [JointSpring(j, x[0], x[1], 0.0, x[2] if len(x) == 3 else 0.0) for j, x in self.springs.items()]
        if springs:
            out.append(forces.JointSprings(mech.model, springs, "added springs", cuts))
        for joint, (value,) in self.torques.items():
            if joint in skip:
                continue
            if joint in cut_names:
                out.append(forces.CutJointEffort(mech.model, cuts, joint, value, f"torque on {joint}"))
            else:
                try:
                    row = forces.TorqueMotor.on_joint(mech.model, joint, value).row
                except InvalidParameters as err:
                    raise InvalidArgument("--torque", joint, err.why) from None
                out.append(forces.TorqueMotor(row, value, name=f"torque on {joint}"))
        return out


def effort_line(name: str, u: Sequence[float]) -> str:
    """One effort's range over the samples where its joint was driven or held (NaN elsewhere: free then).

    Args:
        name: the joint.
        u: (samples,) its effort (N m or N), NaN where the joint was free.

    Returns:
        The line; a joint never driven says so instead of printing NaN.
    """
    driven = [float(x) for x in u if math.isfinite(x)]
    if not driven:
        return f"effort {name}: not computed (the joint was never driven or held in this run)"
    part = "" if len(driven) == len(u) else f", driven at {len(driven)} of {len(u)} samples"
    return f"effort {name}: {min(driven):.4g} .. {max(driven):.4g} (N m or N{part})"


def _simulate(mech, args: argparse.Namespace, inputs, torques, added: _Added, source, file_forces, bars, v0=None):
    """`simulation.simulate` with what the command line gives (file_forces: the description's force elements;
    v0: the initial velocities, `_initial_velocity`)."""
    from mechkit import simulation

    return simulation.simulate(
        mech,
        args.duration,
        inputs=inputs,
        torques=torques,
        forces=_with_tendon_forces(mech, file_forces, added.torques)
        + added.elements(mech, skip=point_to_point_names(file_forces)),
        file_forces=False,
        limits=None if args.no_limits else "file",
        source=source,
        dt=args.dt,
        rtol=args.rtol,
        atol=args.rtol * 1e-2,
        method=args.method,
        dynamics=args.dynamics,
        restitution=args.restitution,
        v0=v0,
        latches=[simulation.Latch(joint, value[0]) for joint, value in added.latches.items()],
        progress=lambda done, total: bars(f"{mech.spec.name} simulate", round(TICKS * done / total), TICKS),
    )


def point_to_point_names(elements: Sequence) -> list[str]:
    """The names of the point-to-point elements among a description's force elements that carry a constant
    force (an MJCF actuator on a spatial tendon, a `<mechkit:strut force>`), which `--torque` may set.

    Args:
        elements: the description's force elements (`mechkit.simulation.default_forces`).

    Returns:
        Their names, in order.
    """
    from mechkit.forces import PointToPointForce

    return [e.name for e in elements if isinstance(e, PointToPointForce) and e.element.law is None]


def _with_tendon_forces(mech, elements: list, torques: dict[str, list[float]]) -> list:
    """The description's force elements with the constant force of each point-to-point element `--torque`
    names replaced by the value given (N along its line, positive lengthens; its spring and damper kept)."""
    import dataclasses

    from mechkit.forces import PointToPointForce

    settable = set(point_to_point_names(elements))
    return [
        PointToPointForce(mech.model, dataclasses.replace(e.element, force=torques[e.name][0]))
        if e.name in settable and e.name in torques
        else e
        for e in elements
    ]


def _initial_velocity(mech, rates: dict[str, list[float]], source):
    """--v0's rates completed to a velocity of the closed loops at home, else an MJCF file's keyframe "home"
    qvel, else None (at rest): `mechkit.simulation.initial`."""
    from mechkit.simulation import initial

    if rates:
        joint_names("--v0", list(rates), mech.model.names[1:], allow_empty=True)
        return initial.rates_velocity(mech, {j: x[0] for j, x in rates.items()}, mech.home_q, "--v0")
    return initial.keyframe_velocity(mech, source, mech.home_q) if source is not None else None


def run(args: argparse.Namespace) -> None:
    """Simulate, print the summary, write what was asked.

    Args:
        args: the parsed command line.

    Raises:
        InvalidArgument: a duration not above 0 s, a restitution outside [0, 1], an output of a format not
            written, a malformed option value (`mechkit.cli.option_values`), a --latch or --spring naming no
            joint of the mechanism, --v0 rates of no joint or that the loops do not allow together.
        MethodUnavailable: the --dynamics asked cannot run on this mechanism (the one that can is named).
    """
    from mechkit import motion, simulation
    from mechkit.simulation.plot import write_plot

    if not args.duration > 0 or not math.isfinite(args.duration):
        raise InvalidArgument("--duration", args.duration, "must be a finite time > 0 s")
    option_values.suffixed("-o", args.output, (".parquet", ".csv"))
    option_values.suffixed("--plot", args.plot, PLOT_SUFFIXES)
    option_values.suffixed("--animate", args.animate, (".html",))
    if not 0 <= args.restitution <= 1:  # else refused per joint limit, or ignored where there is none
        raise InvalidArgument("--restitution", args.restitution, "must be in [0, 1]: 0 stops, 1 bounces back")
    if args.no_limits and args.restitution:
        raise InvalidArgument("--restitution", args.restitution, "applies at the joint limits, which --no-limits drops")
    added = _Added.of(args)
    rates = option_values.named_numbers("--v0", args.v0, "JOINT=RATE (rad/s or m/s)", 1)
    check_writers(args.output, args.plot, "simulation plots")
    if args.animate:
        resolve_output(args.animate)
    mech = load_mechanism(args)
    source = Path(args.name) if Path(args.name).suffix in (".xml", ".mjcf") else None
    file_forces = simulation.default_forces(mech, source, added.threshold)
    cut_joints = [c.name for c in mech.closure_model.closures if c.kind in ("revolute", "prismatic")]
    for option, given, cuts in (
        ("--latch", added.latches, []),
        ("--spring", added.springs, cut_joints),
        ("--torque", added.torques, cut_joints + point_to_point_names(file_forces)),
    ):
        joint_names(option, list(given), list(mech.model.names[1:]) + cuts, allow_empty=True)
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
    if args.base == "moving" and (not args.base_motion or torques is not None):
        raise InvalidArgument(
            "--base", "moving", "needs --base-motion BASE.csv (the carrier's motion; --torques cannot drive it)"
        )
    inputs = carried_inputs(mech, args, inputs)
    bars = ProgressBars(None if args.duration >= LONG_RUN else False)
    try:
        v0 = _initial_velocity(mech, rates, source)
        result = _simulate(mech, args, inputs, torques, added, source, file_forces, bars, v0)
    except MethodUnavailable as err:
        if args.dynamics not in ("proximal", "lcaba"):
            raise
        raise MethodUnavailable(err.method, f"{err.why} (on the command line: --dynamics kkt)") from None
    print(f"{mech.spec.name}: {result.motion.source}")
    print(assembly_line(mech.home_assembly))
    print("\n".join(result.summary()))
    for name in result.motion.effort_names:
        print(effort_line(name, result.motion.effort(name)))
    if args.output:
        parquet = Path(args.output).suffix.lower() == ".parquet"  # the suffix was checked in any case
        writer = simulation.write_parquet if parquet else simulation.write_csv
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
    add_base_arguments(p)
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
        help="the core's forward dynamics (default: proximal; kkt with --friction or on a floating base)",
    )
    p.add_argument(
        "--method",
        default="RK45",
        help="one-step method: RK45 (default), DOP853, RK23, Radau; RK4, SymplecticEuler, ImplicitMidpoint "
        "(fixed step: with --dt only)",
    )
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
        help="a joint spring: stiffness (N m/rad or N/m), reference (rad or m), damping "
        "(a loop-cut joint's too: its frames' relative angle or slide; repeatable)",
    )
    # --- forces helper: constant efforts, limits off, the friction's regularisation
    p.add_argument(
        "--torque",
        action="append",
        metavar="JOINT=VALUE",
        help="a constant torque or force on a joint, a loop-cut joint included (N m or N), or the constant "
        "force of a point-to-point element (an MJCF spatial tendon or its actuator, a <mechkit:strut>: N along it, "
        "positive lengthens; replaces the file's, e.g. an actuator's keyframe control; repeatable)",
    )
    p.add_argument("--no-limits", action="store_true", help="ignore the file's joint limits (nothing stops a joint)")
    p.add_argument(
        "--friction-rate",
        type=float,
        metavar="RATE",
        help="rate (rad/s or m/s) at which friction reaches tanh(1) = 0.76 of its size (default 0.01): "
        "below it friction acts as a damper",
    )
    # --- end of the forces helper's options
    p.add_argument(
        "--restitution", type=float, default=0.0, help="at the file's joint limits: 0 stop (default) .. 1 bounce"
    )
    p.add_argument(
        "--latch", action="append", metavar="JOINT=VALUE", help="a joint that locks at a value (rad or m; repeatable)"
    )
    p.add_argument(
        "--v0",
        action="append",
        metavar="JOINT=RATE",
        help="an initial joint rate (rad/s or m/s; repeatable): the other joints get the rates the loops "
        "need (default: an MJCF file's keyframe 'home' qvel, else at rest)",
    )
    p.add_argument("-o", "--output", help="write the table: .parquet or .csv")
    p.add_argument("--plot", help="write a plot of joints, energies and closure residual (.png, .svg, .pdf)")
    p.add_argument("--animate", metavar="OUT.html", help="write a meshcat animation (self-contained HTML)")
    p.set_defaults(func=run)
