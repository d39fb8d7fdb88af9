"""`mechkit validate`: a second opinion on a mechanism's efforts and reactions by sequential SOC virtual
work over its automatic decomposition, compared with constrained RNEA over its scene."""

from __future__ import annotations

import argparse

from mechkit.base.exceptions import InvalidParameters
from mechkit.base.json_text import dumps
from mechkit.cli.common import add_mechanism_arguments, examples, load_mechanism


def report(args: argparse.Namespace) -> dict:
    """The validation as the JSON contract: name, skcs, max_relative_difference, samples, us_per_sample.

    Each SKC's "indeterminate" lists its unknowns (labelled by the world direction each component was
    chosen from) that its equations leave free at the first state.

    Args:
        args: the parsed command line.

    Returns:
        The JSON contract as a dict.

    Raises:
        InvalidParameters: --samples below 1, or what loading and sampling refuse.
    """
    import warnings

    from mechkit.scenes import SweepStopped
    from mechkit.second_opinion.agreement import agreement, scene_states
    from mechkit.second_opinion.opinion import SecondOpinion

    if args.samples < 1:
        raise InvalidParameters("--samples", args.samples, "must be at least 1")
    mech = load_mechanism(args)
    opinion = SecondOpinion(mech, level=args.level)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SweepStopped)
        states = scene_states(mech, args.samples, scene=args.scene)
    result = agreement(opinion, states)
    first = opinion.solve(*states[0])
    skcs = []
    for s in opinion.skcs:
        labels = s.unknown_labels(opinion.structure)
        free = [
            label
            for label, (joint, k) in zip(labels, s.unknowns, strict=True)
            if (first.free_efforts[joint] if k < 0 else first.free[joint][opinion.structure.joint(joint).components[k]])
        ]
        skcs.append(
            {
                "kind": s.kind,
                "bodies": list(s.bodies),
                "joints": list(s.joints),
                "released": list(s.released),
                "actuators": list(s.actuators),
                "unknowns": labels,
                "equations": s.equations,
                "indeterminate": free,
            }
        )
    return {
        "name": mech.spec.name,
        "level": opinion.level,
        "skcs": skcs,
        "max_relative_difference": result.max_relative_difference,
        "worst": result.worst,
        "determinacy_mismatches": result.determinacy_mismatches,
        "consistency": result.consistency,
        "samples": result.samples,
        "us_per_sample": result.us_per_sample,
        "decompose_us": opinion.decompose_seconds * 1e6,
    }


def format_text(r: dict) -> str:
    """The validation for a reader: the SKCs in solve order, then the agreement and the timings.

    Args:
        r: the validation (`report`).

    Returns:
        The text, lines joined.
    """
    lines = [f"{r['name']}: {len(r['skcs'])} SKCs in solve order ({r['level']} level)"]
    for i, s in enumerate(r["skcs"], 1):
        lines.append(f"  SKC{i} [{s['kind']}] bodies: {', '.join(s['bodies'])}")
        lines.append(
            f"        released: {', '.join(s['released']) or '-'}; actuators: {', '.join(s['actuators']) or '-'}"
        )
        lines.append(
            f"        unknowns: {len(s['unknowns'])}, independent equations: {s['equations']}"
            + (f" ({len(s['unknowns']) - s['equations']} indeterminate)" if len(s["unknowns"]) > s["equations"] else "")
        )
        if s["indeterminate"]:
            shown = ", ".join(s["indeterminate"][:12]) + (" ..." if len(s["indeterminate"]) > 12 else "")
            lines.append(f"        not fixed by statics: {shown}")
    lines.append(
        f"vs constrained RNEA over {r['samples']} samples: max relative difference "
        f"{r['max_relative_difference']:.2e} ({r['worst']}); determinacy mismatches: "
        f"{len(r['determinacy_mismatches'])}; worst SKC residual {r['consistency']:.1e}"
    )
    for method, us in r["us_per_sample"].items():
        lines.append(f"  {method}: {us:.0f} us per sample")
    lines.append(f"  decomposition (once): {r['decompose_us']:.0f} us")
    return "\n".join(lines)


def run(args: argparse.Namespace) -> None:
    """Print the validation.

    Args:
        args: the parsed command line.
    """
    r = report(args)
    print(dumps(r, indent=2) if args.json else format_text(r))


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register `validate`.

    Args:
        sub: the command line's sub-parsers.
    """
    p = sub.add_parser(
        "validate",
        help="second opinion: automatic SOC decomposition vs constrained RNEA",
        **examples("mechkit validate parallel_2t1r", "mechkit validate ten_bar --samples 24 --level body --json"),
    )
    add_mechanism_arguments(p)
    p.add_argument("--samples", type=int, default=12, help="states along the scene (default 12)")
    p.add_argument("--scene", help="scene to sample (default: the mechanism's first, else the sweep)")
    p.add_argument(
        "--level",
        choices=("skc", "body", "component"),
        default="skc",
        help="decomposition granularity: Yang's SKCs (default), whole-body blocks, finest blocks",
    )
    p.add_argument("--json", action="store_true", help="machine-readable output")
    p.set_defaults(func=run)
