"""The failure atlas: where each method fails and how (a growing error, or a clear exception).

The atlas's own studies, of the core's methods on the calibration mechanisms:

- `proximal_mu`: `pin.constraintDynamics` on the four-bar (its 3D point anchor has a zero
  out-of-plane row, i.e. a redundant constraint) as mu -> 0, against the bench's reference (the
  four-bar spec's own: the closed form): mu = 0 gives NaN inside Pinocchio,
  which the core turns into `SingularConfiguration`; the dense KKT on independent rows is unaffected.
- `far_starts`: closure Newton and LM from random starting guesses: converged to the reference
  branch, to another assembly mode, or `ClosureNotConverged`.
- `integration`: four-bar falling under gravity, RK4 and semi-implicit Euler at 1 ms, with and
  without Baumgarte stabilisation: the closure residual drifts without it.

and those the mechanisms declare on their specs (`MechanismSpec.failure_studies`: the five-bar
driven onto its singular pose, the gimbal's resultant losing digits), read through the registry.
`studies` lists them all, `run` runs one, `draw` draws it, `summary_lines` does all three.

A `FailureCase` never holds a NaN error: a non-finite result is recorded as the outcome "non-finite".
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

from mechkit.base.exceptions import MechkitError
from mechkit.bench.charts import pyplot, save_figure
from mechkit.bench.methods import references
from mechkit.bench.sampling import make_samples
from mechkit.catalog import registry
from mechkit.catalog.contract import FailureCase, FailureStudy
from mechkit.loading import load

#: Baumgarte gains (Kp 1/s^2, Kd 1/s) of the stabilised integrations.
BAUMGARTE = (400.0, 40.0)
#: Error drawn for an exact result, and the row the exceptions are marked on (x 10).
FLOOR = 1e-17


def _rel(x, ref) -> float:
    return float(np.max(np.abs(np.asarray(x) - ref)) / max(float(np.max(np.abs(ref))), 1e-300))


# ---------------------------------------------------------------------------- proximal mu
def proximal_mu(quick: bool = True) -> list[FailureCase]:
    """Four-bar (planar and spatial closure rows): constraintDynamics error vs mu, at 1 and 20 iterations.

    Args:
        quick: a few values of mu (else a denser sweep).

    Returns:
        The cases, one per method and mu (condition = mu).
    """
    mus = (
        [0.0, 1e-12, 1e-9, 1e-6, 1e-3, 1e-1] if quick else [0.0, 1e-14, 1e-12, 1e-10, 1e-8, 1e-6, 1e-4, 1e-2, 1e-1, 1.0]
    )
    return [c for rows in ("planar", "spatial") for c in _proximal_rows(rows, mus)]


def _proximal_rows(rows: str, mus: list[float]) -> list[FailureCase]:
    m = load("four_bar", rows=rows)
    s = make_samples(m, 1)[0]
    a_ref = references(m, [s]).a[0]  # sets s.tau to the reference efforts
    cases = [
        FailureCase.attempt(
            "proximal_mu",
            f"constraintDynamics rows={rows} it={it}",
            mu,
            lambda mu=mu, it=it: _rel(m.forward_dynamics(s.q, s.v, s.tau, mu=mu, max_iter=it).a, a_ref),
        )
        for it in (1, 20)
        for mu in mus
    ]
    cases.append(
        FailureCase.attempt(
            "proximal_mu",
            f"dense KKT rows={rows}",
            0.0,
            lambda: _rel(m.forward_dynamics(s.q, s.v, s.tau, "kkt").a, a_ref),
        )
    )
    return cases


# ---------------------------------------------------------------------------- far starts
def far_starts(quick: bool = True, seed: int = 3) -> list[FailureCase]:
    """Closure Newton / LM from uniform random guesses of the passive joints (rad); condition = trial index.

    error = distance (rad) to the reference branch's q; outcome "ok" (reached it), "other branch"
    (closed the loop elsewhere) or the exception.

    Args:
        quick: 20 starts per mechanism (else 200).
        seed: the random generator's seed.

    Returns:
        The cases, one per mechanism, method and start.
    """
    rng = np.random.default_rng(seed)
    n = 20 if quick else 200
    cases = []
    for name in ("four_bar", "five_bar"):
        m = load(name)
        inputs = [m.home_q[m.q_index(j)] for j in m.actuated]
        passive = [i for i in range(m.model.nq) if i not in [m.q_index(j) for j in m.actuated]]
        for k in range(n):
            guess = m.home_q.copy()
            guess[passive] = rng.uniform(-np.pi, np.pi, len(passive))
            for method in ("newton", "lm"):
                try:
                    q = m.assemble(inputs, guess=guess, method=method)
                except MechkitError as e:
                    cases.append(
                        FailureCase("far_starts", f"{name} {method}", k, float("nan"), type(e).__name__, str(e)[:160])
                    )
                    continue
                err = float(np.max(np.abs((q - m.home_q + np.pi) % (2 * np.pi) - np.pi)))
                cases.append(
                    FailureCase("far_starts", f"{name} {method}", k, err, "ok" if err < 1e-8 else "other branch")
                )
    return cases


# ---------------------------------------------------------------------------- integration
def integration(quick: bool = True, duration: float | None = None, dt: float = 1e-3) -> list[FailureCase]:
    """Four-bar released from home at rest under gravity; condition = time (s), error = |closure residual| (m).

    Args:
        quick: 0.5 s of motion (else 2 s), unless `duration` is given.
        duration: the simulated time (s).
        dt: the time step (s).

    Returns:
        The cases: 25 per scheme and stabilisation, along the motion, and the exception where one raised.
    """
    m = load("four_bar")
    duration = duration or (0.5 if quick else 2.0)
    steps = round(duration / dt)
    tau = np.zeros(m.model.nv)
    cases = []
    for scheme in ("RK4", "semi-implicit Euler"):
        for gains, label in (((0.0, 0.0), "no stabilisation"), (BAUMGARTE, "Baumgarte")):

            def acc(q, v, gains=gains):
                return m.forward_dynamics(q, v, tau, baumgarte=gains).a

            q, v = m.home_q.copy(), np.zeros(m.model.nv)
            method = f"{scheme}, {label}"
            try:
                for k in range(1, steps + 1):
                    if scheme == "RK4":
                        k1v, k1a = v, acc(q, v)
                        k2v, k2a = v + 0.5 * dt * k1a, acc(q + 0.5 * dt * k1v, v + 0.5 * dt * k1a)
                        k3v, k3a = v + 0.5 * dt * k2a, acc(q + 0.5 * dt * k2v, v + 0.5 * dt * k2a)
                        k4v, k4a = v + dt * k3a, acc(q + dt * k3v, v + dt * k3a)
                        q = q + dt / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
                        v = v + dt / 6 * (k1a + 2 * k2a + 2 * k3a + k4a)
                    else:
                        v = v + dt * acc(q, v)
                        q = q + dt * v
                    if k % max(1, steps // 25) == 0:
                        cases.append(
                            FailureCase(
                                "integration", method, k * dt, float(np.linalg.norm(m.closure_residual(q))), "ok"
                            )
                        )
            except MechkitError as e:
                cases.append(FailureCase("integration", method, k * dt, float("nan"), type(e).__name__, str(e)[:160]))
    return cases


# ---------------------------------------------------------------------------- the studies
def _own(run):
    """A study of the atlas's own as a `FailureStudy` run: it loads the mechanisms it studies itself."""
    return lambda _mechanism, quick: run(quick)


#: The atlas's own studies (of the core's methods, on the calibration mechanisms they load).
OWN = (
    FailureStudy(
        "proximal_mu",
        _own(proximal_mu),
        condition="proximal regularisation mu (-)",
        error="max |a - a_ref| / max |a_ref| (-)",
    ),
    FailureStudy(
        "far_starts",
        _own(far_starts),
        condition="mechanism and closure solver",
        error="number of random starts (-)",
        counts=True,
    ),
    FailureStudy(
        "integration", _own(integration), condition="time (s)", error="closure residual norm (m)", log_condition=False
    ),
)


def studies(names: Sequence[str] | None = None) -> dict[str, tuple[FailureStudy, str | None]]:
    """Every study of the atlas by name: the atlas's own, then those the named mechanisms (default:
    every registered one) declare, each with the mechanism it runs on (None: it loads its own).

    Args:
        names: the mechanisms whose declared studies are added (default: every registered one).

    Returns:
        Study name -> (the study, the mechanism it runs on, or None when it loads its own).
    """
    found: dict[str, tuple[FailureStudy, str | None]] = {s.name: (s, None) for s in OWN}
    for name in names or registry.names():
        for study in registry.get_spec(name).failure_studies:
            found[study.name] = (study, name)
    return found


def run(study: FailureStudy, mechanism: str | None, quick: bool = True) -> list[FailureCase]:
    """The cases of one study, on the registered mechanism it belongs to (None: the atlas's own study).

    Args:
        study: the study.
        mechanism: the registered mechanism it runs on, or None for an atlas study.
        quick: the study's short form.

    Returns:
        Its cases.
    """
    return study.run(None if mechanism is None else load(mechanism), quick)


# ---------------------------------------------------------------------------- figures and summary
def _conditions(study: FailureStudy, cases: list[FailureCase]) -> np.ndarray:
    """Where each case is drawn along the condition axis (a log axis cannot show 0 or less)."""
    if study.towards_zero:  # 0 (the failure itself) and < 0 (past it) drawn left of the data
        return np.array(
            [c.condition if c.condition > 0 else (10 * FLOOR if c.condition == 0 else FLOOR) for c in cases]
        )
    if study.log_condition:
        return np.array([max(abs(c.condition), FLOOR) for c in cases])
    return np.array([c.condition for c in cases])


def draw(study: FailureStudy, cases: list[FailureCase], folder: Path) -> list[Path]:
    """One figure per study (PNG and SVG): error vs condition per method (or, for a study of counts, the
    number of each outcome per method); exceptions marked with x.

    Args:
        study: the study.
        cases: its cases.
        folder: where the files go.

    Returns:
        The PNG and SVG written as `bench_atlas_<study>`.
    """
    plt = pyplot()

    fig, ax = plt.subplots(figsize=(8, 5))
    methods = list(dict.fromkeys(c.method for c in cases))
    if study.counts:
        outcomes = sorted({c.outcome for c in cases})
        bottom = np.zeros(len(methods))
        for o in outcomes:
            counts = np.array(
                [sum(1 for c in cases if c.method == mm and c.outcome == o) for mm in methods], dtype=float
            )
            ax.bar(range(len(methods)), counts, bottom=bottom, label=o)
            bottom += counts
        ax.set_xticks(range(len(methods)), methods, rotation=20, fontsize=7)
        ax.set_ylabel(study.error)
        ax.set_xlabel(study.condition)
    else:
        for mm in methods:
            pts = [c for c in cases if c.method == mm]
            x = _conditions(study, pts)
            ok = [c.outcome == "ok" for c in pts]
            y = np.array([max(c.error, FLOOR) if o else np.nan for c, o in zip(pts, ok)])
            (line,) = ax.plot(x, y, marker="o", label=mm, markersize=4)
            for xi, c in zip(x, pts):
                if c.outcome != "ok":
                    ax.plot([xi], [FLOOR * 10], marker="x", color=line.get_color(), markersize=9)
                    ax.annotate(c.outcome, (xi, FLOOR * 10), fontsize=6, rotation=60, color=line.get_color())
        ax.set_yscale("log")
        if study.log_condition:
            ax.set_xscale("log")
        if study.towards_zero:
            ax.invert_xaxis()
        if study.note:
            ax.text(0.99, 0.01, study.note, transform=ax.transAxes, fontsize=7, ha="right")
        ax.set_xlabel(study.condition)
        ax.set_ylabel(study.error, fontsize=8)
    ax.set_title(f"failure atlas: {study.name.replace('_', ' ')} (x: raised, at the bottom)", fontsize=9)
    return save_figure(fig, ax, folder, f"bench_atlas_{study.name}")


def summary_lines(folder: Path, quick: bool = True) -> list[str]:
    """Run every study, draw its figure in `folder`, and return markdown lines describing the outcomes.

    Args:
        folder: where the figures go.
        quick: every study's short form.

    Returns:
        Markdown lines: per study, per method, how many cases succeeded, their error range and where the first
            exception came.
    """
    lines = []
    for name, (study, mechanism) in studies().items():
        cases = run(study, mechanism, quick)
        with np.errstate(all="ignore"):
            draw(study, cases, folder)
        lines.append(f"- **{name}** (`bench_atlas_{name}.png`):")
        for method in dict.fromkeys(c.method for c in cases):
            pts = [c for c in cases if c.method == method]
            ok = [c for c in pts if c.outcome == "ok"]
            raised = sorted({c.outcome for c in pts if c.outcome != "ok"})
            worst = f"error {min(c.error for c in ok):.1e} .. {max(c.error for c in ok):.1e}" if ok else "no result"
            first = next((c for c in pts if c.outcome != "ok"), None)
            fail = f"; {', '.join(raised)} from condition {first.condition:g}" if first else ""
            lines.append(f"  - {method}: {len(ok)}/{len(pts)} ok, {worst}{fail}")
    return lines
