"""The bench in words: per-mechanism tables (plain text or GitHub markdown), the goals' verdicts, and
the benchmarks page (docs/benchmarks.md). Text only: the command line prints and writes it."""

from __future__ import annotations

import os
import platform
from importlib import metadata
from pathlib import Path

import numpy
import numpy as np
import pinocchio
import scipy

from mechkit.bench.errors import ERROR_LABELS
from mechkit.bench.loadtime import FirstLoad, quartiles
from mechkit.bench.methods import BASELINES
from mechkit.bench.results import MechanismBench
from mechkit.bench.scale import ScaleFit
from mechkit.bench.timing import EQUAL_ACCURACY_FLOOR

#: How to read the peers' rows (docs/benchmarks.md).
PEER_NOTES = """\
- MuJoCo runs the MJCF of `mechkit export NAME --format mjcf` (same tree, `equality` connect/weld at
  the cuts). Its equality constraints are soft: at the default solref/solimp the closure gives way.
  At rest the four-bar's accelerations are off by ~1 % of their gravity-driven size (~1e2 rad/s^2);
  the bench's states move slowly (|a| ~ 1 rad/s^2, the efforts holding gravity), so the same softness
  reads as an O(1)-O(10) relative error here. "Stiff" (impedance 0.9999, time constant 2 ms) narrows
  it to ~1e-5 of the gravity scale.
  `mj_forward` is timed with the efforts as `qfrc_applied`. Its inverse dynamics row is
  `mj_inverse` plus our least-squares split of M a + c on MuJoCo's constraint Jacobian (MuJoCo has no
  such split): it is exact because the split is, and reports efforts only.
- Drake (when installed: `pip install drake`) runs a discrete `MultibodyPlant` (SAP, dt = 1 ms) with
  ball constraints at the cuts; the row is (v_next - v) / dt of one step. SAP imposes the closure on
  the next velocity at the current configuration, so one step misses the velocity-product term of
  the closure acceleration (J a = -J'v): its error does not shrink with dt at states with velocity.
  Its reaction-forces port gives the tree joints' reactions of that step (the cut constraints' own
  forces it does not report); they stand beside mechkit's rigid reactions and MuJoCo's soft ones in
  [Rigid reactions beside the engines' soft ones](reactions_vs_engines.md), not in these timing rows.
- The core's inverse-dynamics rows give every joint's reaction; the numpy methods of four_bar and
  five_bar start from the link motion of the closed form (their times exclude that conversion).
"""


def _us(x: float) -> str:
    return "-" if not np.isfinite(x) else f"{x * 1e6:.2f}"


def _num(x: float, fmt: str = ".1e") -> str:
    return "-" if not np.isfinite(x) else format(x, fmt)


def format_table(b: MechanismBench, markdown: bool = False) -> str:
    """The per-mechanism table (plain text or GitHub markdown).

    Args:
        b: one mechanism's bench rows.
        markdown: GitHub markdown instead of plain text.

    Returns:
        The table's text, with its heading.
    """
    head = ["quantity", "method", "us/call", "IQR us", "error", "x fastest", "x base", "outcome"]
    lines = []
    body = []
    for r in b.rows:
        iqr = r.p75_s - r.p25_s
        outcome = r.outcome if r.outcome != "ok" else (r.note or "ok")
        name = ("[peer] " if r.method.peer else "") + r.method.name
        body.append(
            [
                r.method.quantity,
                name,
                _us(r.median_s),
                _us(iqr),
                _num(r.error),
                _num(r.x_fastest, ".2f"),
                _num(r.x_base, ".2f"),
                outcome,
            ]
        )
    if markdown:
        lines.append("| " + " | ".join(head) + " |")
        lines.append("|" + "---|" * len(head))
        lines += ["| " + " | ".join(c.replace("|", "/") for c in row) + " |" for row in body]
    else:
        widths = [max(len(h), *(len(row[i]) for row in body)) for i, h in enumerate(head[:-1])]
        fmt = "  ".join(f"{{:<{w}}}" for w in widths) + "  {}"
        lines.append(fmt.format(*head))
        lines += [fmt.format(*row) for row in body]
    refs = "; ".join(f"{q}: {label}" for q, label in b.references.items())
    title = f"{b.name} (nv={b.nv}, closure rows={b.rows_closure})"
    if markdown:
        return f"### {title}\n\nReferences: {refs}.\n\n" + "\n".join(lines) + "\n"
    return f"== {title}\nreferences: {refs}\n" + "\n".join(lines) + "\n"


def machine() -> dict[str, str]:
    """Machine and versions, for the record."""
    info = {
        "python": platform.python_version(),
        "platform": platform.platform(),
        "processor": _cpu(),
        "cores": str(os.cpu_count()),
        "pinocchio": pinocchio.__version__,
        "numpy": numpy.__version__,
        "scipy": scipy.__version__,
    }
    for dist in ("mujoco", "drake", "matplotlib"):
        try:
            info[dist] = metadata.version(dist)
        except metadata.PackageNotFoundError:
            info[dist] = "not installed"
    return info


def _cpu() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def goals(results: list[MechanismBench]) -> list[str]:
    """The issue's two goals, from back-to-back (paired) timings: one line per mechanism and goal.

    Args:
        results: the bench of each mechanism.

    Returns:
        The lines, each met or missed (and why).
    """
    out = []
    for b in results:
        by = {r.method.name: r for r in b.rows if r.outcome == "ok"}
        mj = by.get("MuJoCo mj_forward (default solref/solimp)")
        fd = by.get(BASELINES["forward_dynamics"])
        idr = by.get("constrained RNEA, no determinacy")
        p = b.paired
        if mj and fd and "fd/mujoco" in p:
            acc = mj.error / max(fd.error, 1e-300)
            id_ratio = p.get("id/mujoco", float("inf"))
            met = p["fd/mujoco"] <= 1.0 and id_ratio <= 1.0 and acc >= 1e6
            raw_ok = p.get("raw/mujoco", float("inf")) <= 1.0
            missed = [
                what
                for what, bad in (
                    (
                        "forward dynamics slower"
                        + (
                            ": the raw Pinocchio call is faster than MuJoCo, the wrapper's Python overhead is not"
                            if raw_ok
                            else ": the raw pin.constraintDynamics itself is slower here (legacy "
                            "proximal path, see the scale fit)"
                        ),
                        p["fd/mujoco"] > 1.0,
                    ),
                    (
                        (
                            "reactions slower: Python overhead of the core's inverse dynamics, see "
                            "tools/bench_core.py --profile"
                        ),
                        id_ratio > 1.0,
                    ),
                    ("accuracy < 1e6x", acc < 1e6),
                )
                if bad
            ]
            raw = f" (raw pin.constraintDynamics {p['raw/mujoco']:.2f})" if "raw/mujoco" in p else ""
            out.append(
                f"{b.name}: time / MuJoCo mj_forward: constrained forward dynamics {p['fd/mujoco']:.2f}{raw}, inverse "
                f"dynamics with reactions {id_ratio:.2f}; error {fd.error:.1e} vs MuJoCo default {mj.error:.1e} "
                f"({acc:.1e}x): {'MET' if met else 'MISSED (' + ', '.join(missed) + ')'}"
            )
        if "id/raw" in p:
            det = f", with determinacy {p['id+det/raw']:.1f}x" if "id+det/raw" in p else ""
            err = f" (error {idr.error:.1e})" if idr else ""
            out.append(
                f"{b.name}: inverse dynamics with every reaction / one raw pin.constraintDynamics: "
                f"{p['id/raw']:.1f}x{err}{det}: "
                + (
                    "MET (goal 5x)"
                    if p["id/raw"] <= 5
                    else "MISSED (goal 5x): Python-level numpy work around the "
                    "Pinocchio calls dominates, see tools/bench_core.py --profile"
                )
            )
    return out


def goal_summary(results: list[MechanismBench]) -> str:
    """One paragraph: how many mechanisms meet each goal, from the paired timings.

    Args:
        results: the bench of each mechanism.

    Returns:
        The paragraph.
    """
    n = len(results)
    p = [b.paired for b in results]
    fd = sum(1 for x in p if x.get("fd/mujoco", np.inf) <= 1.0)
    raw = sum(1 for x in p if x.get("raw/mujoco", np.inf) <= 1.0)
    idm = sum(1 for x in p if x.get("id/mujoco", np.inf) <= 1.0)
    inaccurate = []
    for b in results:
        by = {r.method.name: r for r in b.rows if r.outcome == "ok"}
        mj, ours = by.get("MuJoCo mj_forward (default solref/solimp)"), by.get(BASELINES["forward_dynamics"])
        if not (mj and ours and mj.error >= 1e6 * ours.error):
            inaccurate.append(b.name)
    acc = n - len(inaccurate)
    idr = sum(1 for x in p if x.get("id/raw", np.inf) <= 5.0)
    return (
        f"Goal 1 (our constrained dynamics and reactions at least as fast as MuJoCo's forward step, 1e6x more "
        f"accurate than its default soft constraints): accuracy met on {acc}/{n}"
        + (f" (missed: {', '.join(inaccurate)}: see its table, our own methods disagree there)" if inaccurate else "")
        + f"; speed of the forward-dynamics "
        f"wrapper met on {fd}/{n} (the raw pin.constraintDynamics call on {raw}/{n}); inverse dynamics with every "
        f"reaction as fast as mj_forward on {idm}/{n}. Goal 2 (inverse dynamics with every reaction within 5x of "
        f"one raw pin.constraintDynamics): met on {idr}/{n}. Where speed is missed, the cost is Python-level "
        f"work around the Pinocchio calls (see tools/bench_core.py --profile), except where the raw "
        f"pin.constraintDynamics call is itself slower than mj_forward ({n - raw}/{n}: Pinocchio's legacy proximal "
        f"path: see its exponent in the scale fit)."
    )


def first_load_lines(first: FirstLoad) -> list[str]:
    """The first load in a fresh process: times (median and quartiles, ms) and the mechanism modules imported.

    Args:
        first: the timed first loads.

    Returns:
        A markdown table and a sentence on the modules imported.
    """
    rows = []
    for label, values in (
        ("whole process (interpreter start, imports, load)", first.process_s),
        ("`import mechkit` + `mechkit.load`, timed inside the process", first.inside_s),
    ):
        median, p25, p75 = quartiles(values)
        rows.append(f"| {label} | {median * 1e3:.0f} | {p25 * 1e3:.0f} .. {p75 * 1e3:.0f} | {len(values)} |")
    verdict = (
        "no other mechanism's module: MET"
        if not first.others
        else f"other mechanisms' modules imported: {', '.join(first.others)}: MISSED"
    )
    return [
        "| first load | median ms | 25 .. 75 % ms | runs |",
        "|---|---|---|---|",
        *rows,
        "",
        (
            f"Mechanism modules imported by `mechkit.load({first.name!r})`: {', '.join(first.modules) or 'none'} "
            f"({verdict})."
        ),
    ]


def markdown_report(
    results: list[MechanismBench],
    quick: bool,
    charts: list[Path],
    failures: list[str],
    skipped: dict[str, str],
    fits: list[ScaleFit],
    first: FirstLoad | None = None,
    sections: dict[str, list[str]] | None = None,
) -> str:
    """docs/benchmarks.md: machine, goals, per-mechanism tables, scale fits, extra sections, first load,
    skipped mechanisms, failure atlas, charts.

    Args:
        results: the bench of each mechanism.
        quick: whether the run was `--quick` (named in the page's header).
        charts: the chart files (the PNGs are linked from figures/).
        failures: the failure atlas's lines.
        skipped: mechanism -> why it was not measured.
        fits: the cost-against-nv fits (method, points, exponent).
        first: the first-load timings, if measured.
        sections: extra sections, title -> lines (e.g. `bench --speed`'s).

    Returns:
        The page's markdown text.
    """
    lines = [
        "# Benchmarks",
        "",
        "Generated by `mechkit bench"
        + (" --quick" if quick else "")
        + " --markdown docs/benchmarks.md` (do not edit by hand). Times are medians over repeats in one",
        "process on a shared machine: compare within a table, not across runs.",
        "",
        "## Machine",
        "",
    ]
    lines += [f"- {k}: {v}" for k, v in machine().items()]
    lines += ["", "## Goals", "", goal_summary(results), ""] + [f"- {g}" for g in goals(results)]
    lines += [
        "",
        "## Peers and methods",
        "",
        PEER_NOTES,
        "## Columns",
        "",
        (
            f"error: per quantity, {'; '.join(f'{q}: {e}' for q, e in ERROR_LABELS.items())}. "
            f"x fastest: time / fastest method of equal or better accuracy (error within 10x, or both <= "
            f"{EQUAL_ACCURACY_FLOOR:g}; efforts-only rows are not counted against rows with reactions). "
            f"x base: time / the baseline ({'; '.join(f'{q}: {m}' for q, m in BASELINES.items())})."
        ),
        "",
        "## Results",
        "",
    ]
    for b in results:
        lines.append(format_table(b, markdown=True))
    if fits:
        lines += [
            "## Scale",
            "",
            ("Time per call against nv (mechanisms timed round-robin), least-squares fit of log t = p log nv + c."),
            "",
            "| method | p | points (mechanism nv: us) |",
            "|---|---|---|",
        ]
        for name, pts, slope in fits:
            lines.append(f"| {name} | {slope:.2f} | " + ", ".join(f"{m} {n}: {t * 1e6:.1f}" for m, n, t in pts) + " |")
        lines.append("")
    for title, body in (sections or {}).items():
        lines += [f"## {title}", "", *body, ""]
    if first is not None:
        lines += [
            "## First load",
            "",
            (
                f"`python -c \"import mechkit; mechkit.load('{first.name}')\"` in fresh processes, "
                "after one untimed run that warms the bytecode cache."
            ),
            "",
            *first_load_lines(first),
            "",
        ]
    if skipped:
        lines += ["## Not measured", ""] + [f"- {k}: {v}" for k, v in skipped.items()] + [""]
    if failures:
        lines += ["## Failure atlas", ""] + failures + [""]
    if charts:
        lines += ["## Charts", ""] + [f"![{p.stem}](figures/{p.name})" for p in charts if p.suffix == ".png"] + [""]
    return "\n".join(lines)


def replace_section(path: str | Path, heading: str, section: str) -> None:
    """Put a section into a Markdown file: in place of the text under its heading (up to the next "## "),
    else at the end; the rest of the file is kept.

    Args:
        path: the Markdown file, rewritten in place (atomically).
        heading: the section's heading line ("## ...").
        section: its text, heading first.
    """
    from mechkit.base.atomic import write_text

    text = Path(path).read_text()
    if heading in text:
        head, _, rest = text.partition(heading)
        tail = rest.split("\n## ", 1)
        text = head + section + ("\n## " + tail[1] if len(tail) == 2 else "")
    else:
        text = text.rstrip("\n") + "\n\n" + section
    write_text(path, text)
