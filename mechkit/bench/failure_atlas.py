"""The failure atlas: where each method fails and how (a growing error, or a clear exception).

Five studies, each returning `Case`s (one per method and condition) and drawn by `draw`:

- `singularity`: the five-bar driven towards the pose where its distal bars are collinear (the
  passive block of the closure Jacobian loses rank); velocities, forward and inverse dynamics
  against the closed form, until the core refuses with `SingularConfiguration` and, past it, the
  linkage cannot assemble (`ClosureNotConverged`).
- `proximal_mu`: `pin.constraintDynamics` on the four-bar (its 3D point anchor has a zero
  out-of-plane row, i.e. a redundant constraint) as mu -> 0, against the bench's reference (the
  four-bar spec's own: the closed form): mu = 0 gives NaN inside Pinocchio,
  which the core turns into `SingularConfiguration`; the dense KKT on independent rows is unaffected.
- `far_starts`: closure Newton and LM from random starting guesses: converged to the reference
  branch, to another assembly mode, or `ClosureNotConverged`.
- `integration`: four-bar falling under gravity, RK4 and semi-implicit Euler at 1 ms, with and
  without Baumgarte stabilisation: the closure residual drifts without it.
- `root_loss`: rocket gimbal forward kinematics by the resultant: the degree-8 eliminant against
  the paper's degree-16 form, whose four-fold roots at +-i cost digits.

A `Case` never holds a NaN error: a non-finite result is recorded as the outcome "non-finite".
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mechkit.base.exceptions import MechkitError
from mechkit.bench.charts import pyplot, save_figure
from mechkit.bench.methods import references
from mechkit.bench.sampling import make_samples
from mechkit.loading import load
from mechkit.mechanisms.rocket_gimbal import resultant as res
from mechkit.mechanisms.rocket_gimbal.params import geometry
from mechkit.validation.planar_closed_form import FiveBarGeometry, five_bar
from mechkit.validation.planar_newton_euler import newton_euler

#: Baumgarte gains (Kp 1/s^2, Kd 1/s) of the stabilised integrations.
BAUMGARTE = (400.0, 40.0)


@dataclass(frozen=True)
class Case:
    """One method at one condition: `error` (finite, or nan when it raised) and `outcome`."""

    study: str
    method: str
    condition: float
    error: float
    outcome: str  # "ok", "non-finite", or the exception class name
    message: str = ""


def _attempt(study: str, method: str, condition: float, fn) -> Case:
    try:
        err = float(fn())
    except MechkitError as e:
        return Case(study, method, condition, float("nan"), type(e).__name__, str(e)[:160])
    if not np.isfinite(err):
        return Case(study, method, condition, float("nan"), "non-finite")
    return Case(study, method, condition, err, "ok")


def _rel(x, ref) -> float:
    return float(np.max(np.abs(np.asarray(x) - ref)) / max(float(np.max(np.abs(ref))), 1e-300))


# ---------------------------------------------------------------------------- singularity
def _five_bar_inputs(gap: float) -> np.ndarray:
    """Proximal angles (rad) at which |B1 B2| = dist1 + dist2 - gap (default geometry), theta2 = 0.3."""
    g = FiveBarGeometry()
    theta2 = 0.3
    b2 = np.array([g.ground + g.prox2 * np.cos(theta2), g.prox2 * np.sin(theta2)])
    target = g.dist1 + g.dist2 - gap
    # theta1 in (pi/2, pi): |B1 B2| grows monotonically as B1 swings away from B2
    lo, hi = np.pi / 2, np.pi
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        d = np.hypot(*(g.prox1 * np.array([np.cos(mid), np.sin(mid)]) - b2))
        lo, hi = (mid, hi) if d < target else (lo, mid)
    return np.array([0.5 * (lo + hi), theta2])


def singularity(quick: bool = True) -> list[Case]:
    """Five-bar approaching distal collinearity: gap (m) from 1e-2 down to 1e-14, 0, then past it."""
    m = load("five_bar")
    gaps = np.logspace(-2, -14, 7 if quick else 13).tolist() + [0.0, -1e-3]
    cases: list[Case] = []
    q = m.home_q
    for gap in gaps:
        q = _singular_point(m, gap, q, cases)
    return cases


def _singular_point(m, gap: float, q_prev: np.ndarray, cases: list[Case]) -> np.ndarray:
    """Cases of every method at one gap (m); returns the assembled q (or q_prev) to start the next gap from."""
    rates, accs = np.array([0.3, -0.2]), np.array([0.5, 0.4])
    order = [m.v_index(j) for j in ("prox1", "dist1", "prox2", "dist2")]
    th = _five_bar_inputs(gap)
    try:
        st = five_bar(tuple(th), tuple(rates), tuple(accs))
        dyn = newton_euler(st)
    except MechkitError as e:
        st = dyn = None
        cases.append(Case("singularity", "closed form + Newton-Euler (reference)", gap, float("nan"), type(e).__name__, str(e)[:160]))
    guess = q_prev
    if st is not None:
        guess = np.zeros(m.model.nq)
        guess[order] = st.q
    # error vs the closed form; with no reference (at or past the singular pose) the residual it reached
    case = _attempt("singularity", "assembly (closure Newton)", gap,
                    lambda: np.linalg.norm(m.closure_residual(m.assemble(th, guess=guess))) if st is None
                    else _rel(m.assemble(th, guess=guess)[order], st.q))
    cases.append(case)
    if case.outcome != "ok":
        return q_prev
    q = m.assemble(th, guess=guess)
    cases.append(Case("singularity", "passive-block condition number", gap, m.singularity(q), "ok"))
    J = m.closure_jacobian(q)
    if st is None:  # at the singular pose itself: no reference; error = the method's own closure residual
        zero = np.zeros(m.model.nv)
        cases.append(_attempt("singularity", "velocities (core)", gap, lambda: np.linalg.norm(J @ m.velocities(q, rates))))
        for method, label in (("proximal", "forward dynamics, proximal"), ("kkt", "forward dynamics, dense KKT")):
            cases.append(_attempt("singularity", label, gap,
                                  lambda method=method: np.linalg.norm(J @ m.forward_dynamics(q, zero, zero, method).a)))
        return q
    v_ref, a_ref, tau = np.zeros(4), np.zeros(4), np.zeros(4)
    v_ref[order], a_ref[order] = st.qd, st.qdd
    efforts = np.array([dyn.efforts["prox1"], dyn.efforts["prox2"]])
    tau[[m.v_index("prox1"), m.v_index("prox2")]] = efforts
    cases.append(_attempt("singularity", "velocities (core)", gap, lambda: _rel(m.velocities(q, rates), v_ref)))
    for method, label in (("proximal", "forward dynamics, proximal"), ("kkt", "forward dynamics, dense KKT")):
        cases.append(_attempt("singularity", label, gap, lambda method=method: _rel(m.forward_dynamics(q, v_ref, tau, method).a, a_ref)))
    cases.append(_attempt("singularity", "inverse dynamics (efforts)", gap, lambda: _rel(
        [m.inverse_dynamics(q, v_ref, a_ref, determinacy=False).efforts[j] for j in ("prox1", "prox2")], efforts)))
    return q


# ---------------------------------------------------------------------------- proximal mu
def proximal_mu(quick: bool = True) -> list[Case]:
    """Four-bar (planar and spatial closure rows): constraintDynamics error vs mu, at 1 and 20 iterations."""
    mus = [0.0, 1e-12, 1e-9, 1e-6, 1e-3, 1e-1] if quick else [0.0, 1e-14, 1e-12, 1e-10, 1e-8, 1e-6, 1e-4, 1e-2, 1e-1, 1.0]
    return [c for rows in ("planar", "spatial") for c in _proximal_rows(rows, mus)]


def _proximal_rows(rows: str, mus: list[float]) -> list[Case]:
    m = load("four_bar", rows=rows)
    s = make_samples(m, 1)[0]
    a_ref = references(m, [s]).a[0]  # sets s.tau to the reference efforts
    cases = [_attempt("proximal_mu", f"constraintDynamics rows={rows} it={it}", mu,
                      lambda mu=mu, it=it: _rel(m.forward_dynamics(s.q, s.v, s.tau, mu=mu, max_iter=it).a, a_ref))
             for it in (1, 20) for mu in mus]
    cases.append(_attempt("proximal_mu", f"dense KKT rows={rows}", 0.0, lambda: _rel(m.forward_dynamics(s.q, s.v, s.tau, "kkt").a, a_ref)))
    return cases


# ---------------------------------------------------------------------------- far starts
def far_starts(quick: bool = True, seed: int = 3) -> list[Case]:
    """Closure Newton / LM from uniform random guesses of the passive joints (rad); condition = trial index.

    error = distance (rad) to the reference branch's q; outcome "ok" (reached it), "other branch"
    (closed the loop elsewhere) or the exception.
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
                    cases.append(Case("far_starts", f"{name} {method}", k, float("nan"), type(e).__name__, str(e)[:160]))
                    continue
                err = float(np.max(np.abs((q - m.home_q + np.pi) % (2 * np.pi) - np.pi)))
                cases.append(Case("far_starts", f"{name} {method}", k, err, "ok" if err < 1e-8 else "other branch"))
    return cases


# ---------------------------------------------------------------------------- integration
def integration(quick: bool = True, duration: float | None = None, dt: float = 1e-3) -> list[Case]:
    """Four-bar released from home at rest under gravity; condition = time (s), error = |closure residual| (m)."""
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
                        cases.append(Case("integration", method, k * dt, float(np.linalg.norm(m.closure_residual(q))), "ok"))
            except MechkitError as e:
                cases.append(Case("integration", method, k * dt, float("nan"), type(e).__name__, str(e)[:160]))
    return cases


# ---------------------------------------------------------------------------- root loss
def root_loss(quick: bool = True) -> list[Case]:
    """Rocket gimbal FK: pose error (rad) of the degree-8 eliminant and the degree-16 form vs closure Newton.

    condition = stroke dlA - dlB (m) along a line through the equal-stroke diagonal, where roots
    of the resultant become double.
    """
    m = load("rocket_gimbal")
    geo = geometry(m.params)
    cases = []
    offsets = [1e-2, 1e-4, 1e-6, 0.0] if quick else [1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-8, 0.0]
    base = 0.05
    for off in offsets:
        stroke = np.array([base + off, base])
        try:
            eqs = res.half_angle_equations(geo, stroke)
            exact = res.pick_in_range(res.fk_resultant(geo, stroke))
        except MechkitError as e:
            cases.append(Case("root_loss", "resultant + polish (reference)", off, float("nan"), type(e).__name__, str(e)[:160]))
            continue
        for label, poly in (("degree-8 eliminant roots", res.sylvester_resultant(eqs)),
                            ("degree-16 form roots", res.degree16_polynomial(eqs))):
            roots = poly.roots()
            real = roots[np.abs(roots.imag) <= 1e-7 * (1 + np.abs(roots))].real
            if real.size == 0:
                cases.append(Case("root_loss", label, off, float("nan"), "root lost", "no real root passed the 1e-7 imaginary-part test"))
                continue
            err = float(np.min(np.abs(2 * np.arctan(real) - exact.alpha)))
            cases.append(Case("root_loss", label, off, err, "ok"))
    return cases


STUDIES = {"singularity": singularity, "proximal_mu": proximal_mu, "far_starts": far_starts,
           "integration": integration, "root_loss": root_loss}


# ---------------------------------------------------------------------------- figures and summary
def draw(study: str, cases: list[Case], folder: Path) -> list[Path]:
    """One figure per study (PNG and SVG): error vs condition per method; exceptions marked with x."""
    plt = pyplot()

    fig, ax = plt.subplots(figsize=(8, 5))
    methods = list(dict.fromkeys(c.method for c in cases))
    if study == "far_starts":
        outcomes = sorted({c.outcome for c in cases})
        bottom = np.zeros(len(methods))
        for o in outcomes:
            counts = np.array([sum(1 for c in cases if c.method == mm and c.outcome == o) for mm in methods], dtype=float)
            ax.bar(range(len(methods)), counts, bottom=bottom, label=o)
            bottom += counts
        ax.set_xticks(range(len(methods)), methods, rotation=20, fontsize=7)
        ax.set_ylabel("number of random starts (-)")
        ax.set_xlabel("mechanism and closure solver")
    else:
        xlabel = {"singularity": "distance to the singular pose: dist1 + dist2 - |B1B2| (m)",
                  "proximal_mu": "proximal regularisation mu (-)", "integration": "time (s)",
                  "root_loss": "stroke difference dlA - dlB (m)"}[study]
        ylabel = {"singularity": "relative error vs closed form (-); condition number for the cond row",
                  "proximal_mu": "max |a - a_ref| / max |a_ref| (-)", "integration": "closure residual norm (m)",
                  "root_loss": "alpha error vs polished resultant (rad)"}[study]
        floor = 1e-17
        for mm in methods:
            pts = [c for c in cases if c.method == mm]
            if study == "singularity":  # gap 0 (singular pose) and < 0 (cannot assemble) drawn left of the data
                x = np.array([c.condition if c.condition > 0 else (1e-16 if c.condition == 0 else 1e-17) for c in pts])
            else:
                x = np.array([max(abs(c.condition), floor) for c in pts])
            ok = [c.outcome == "ok" for c in pts]
            y = np.array([max(c.error, floor) if o else np.nan for c, o in zip(pts, ok)])
            line, = ax.plot(x, y, marker="o", label=mm, markersize=4)
            bad = [(xi, c.outcome) for xi, c in zip(x, pts) if c.outcome != "ok"]
            for xi, outcome in bad:
                ax.plot([xi], [floor * 10], marker="x", color=line.get_color(), markersize=9)
                ax.annotate(outcome, (xi, floor * 10), fontsize=6, rotation=60, color=line.get_color())
        ax.set_yscale("log")
        if study != "integration":
            ax.set_xscale("log")
        if study == "singularity":
            ax.invert_xaxis()
        if study == "singularity":
            ax.text(0.99, 0.01, "x = 1e-16: at the singular pose; 1e-17: 1 mm past it", transform=ax.transAxes,
                    fontsize=7, ha="right")
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel, fontsize=8)
    ax.set_title(f"failure atlas: {study.replace('_', ' ')} (x: raised, at the bottom)", fontsize=9)
    return save_figure(fig, ax, folder, f"bench_atlas_{study}")


def summary_lines(folder: Path, quick: bool = True) -> list[str]:
    """Run every study, draw its figure in `folder`, and return markdown lines describing the outcomes."""
    lines = []
    for study, fn in STUDIES.items():
        cases = fn(quick)
        with np.errstate(all="ignore"):
            draw(study, cases, folder)
        lines.append(f"- **{study}** (`bench_atlas_{study}.png`):")
        for method in dict.fromkeys(c.method for c in cases):
            pts = [c for c in cases if c.method == method]
            ok = [c for c in pts if c.outcome == "ok"]
            raised = sorted({c.outcome for c in pts if c.outcome != "ok"})
            worst = f"error {min(c.error for c in ok):.1e} .. {max(c.error for c in ok):.1e}" if ok else "no result"
            first = next((c for c in pts if c.outcome != "ok"), None)
            fail = f"; {', '.join(raised)} from condition {first.condition:g}" if first else ""
            lines.append(f"  - {method}: {len(ok)}/{len(pts)} ok, {worst}{fail}")
    return lines
