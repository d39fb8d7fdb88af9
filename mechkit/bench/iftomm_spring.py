"""The IFToMM four-bar with a diagonal spring (tests/fixtures/iftomm/spring_four_bar.urdf): its static
equilibrium and the eigenvalues of the motion linearised there, by mechkit (`Mechanism.equilibrium`,
`mechkit.simulation.small_oscillations`) against the closed form of the rhombus and the published angle.

The closed form (independent of mechkit): at the equilibrium the linkage is a rhombus with every bar at the
rocker's angle phi, so the potential is V = 2 g sin(phi) + k/2 (2 cos(phi/2) - L0)^2 (three 1 kg rods: the
crank's and rocker's centres at sin(phi)/2, the coupler's at sin(phi); the spring from O to C, |OC| =
2 cos(phi/2)), the kinetic energy (1/3 + 1/3 + 1) phi'^2 / 2 (two rods about their pivots, the coupler in
translation) and the damper's rate -sin(phi/2) phi'; phi from V' = 0 (scipy's brentq) and the eigenvalues the
roots of (5/3) s^2 + c sin^2(phi/2) s + V''(phi) = 0.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.optimize import brentq

from mechkit.bench.markdown import replace_section
from mechkit.loading import load
from mechkit.simulation.small_oscillations import small_oscillations

FIXTURE = Path(__file__).resolve().parents[2] / "tests" / "fixtures" / "iftomm" / "spring_four_bar.urdf"
HEADING = "## Equilibrium and eigenvalues: the four-bar with a diagonal spring"
#: The benchmark's equilibrium angle of the rocker (rad), as published to twelve digits.
PUBLISHED_PHI = 2.23433101898
#: Gravity (m/s^2), spring stiffness (N/m), damping (N s/m) and free length (m; ours: the square's diagonal).
G, STIFFNESS, DAMPING, FREE_LENGTH = 9.81, 25.0, 1.0, float(np.sqrt(2.0))
#: The published solution (EoM, B. Minaker): its accuracy and CPU time (s), its page.
PUBLISHED_SOLUTION = "EoM (Matlab): accuracy 2.4e-11, 7.5 s (iftomm-multibody.org/benchmark/solution/120)"


@dataclass(frozen=True)
class SpringFourBarResult:
    """mechkit's answer and the closed form's.

    Attributes:
        phi: the rocker's equilibrium angle by mechkit (rad).
        phi_exact: the closed form's (rad).
        eigenvalues: (2,) mechkit's (1/s).
        eigenvalues_exact: (2,) the closed form's (1/s).
        residual: the equilibrium's reduced force (N m).
        cpu: CPU time of the load, equilibrium and eigenvalues (s; the fastest of the repeats).
    """

    phi: float
    phi_exact: float
    eigenvalues: np.ndarray
    eigenvalues_exact: np.ndarray
    residual: float
    cpu: float

    @property
    def eigenvalue_error(self) -> float:
        """Largest relative difference of mechkit's eigenvalues from the closed form's."""
        return float(np.max(np.abs(self.eigenvalues - self.eigenvalues_exact) / np.abs(self.eigenvalues_exact)))


def closed_form() -> tuple[float, np.ndarray]:
    """The rhombus's equilibrium angle and eigenvalues (see the module docstring).

    Returns:
        (phi (rad), (2,) the roots s (1/s) sorted by real then imaginary part).
    """
    k, L0 = STIFFNESS, FREE_LENGTH

    def dV(p: float) -> float:
        return 2 * G * np.cos(p) - k * (2 * np.cos(p / 2) - L0) * np.sin(p / 2)

    phi = float(brentq(dV, 1.9, 2.6, xtol=1e-15, rtol=4 * np.finfo(float).eps))
    K = -2 * G * np.sin(phi) + k * np.sin(phi / 2) ** 2 - k / 2 * (2 * np.cos(phi / 2) - L0) * np.cos(phi / 2)
    roots = np.roots([5 / 3, DAMPING * np.sin(phi / 2) ** 2, K])
    return phi, roots[np.lexsort((roots.imag, roots.real))]


def measure(repeats: int = 5) -> SpringFourBarResult:
    """mechkit on the fixture: load, equilibrium from the file's guess, eigenvalues; and the closed form.

    Args:
        repeats: timed runs (the fastest kept).

    Returns:
        The `SpringFourBarResult`.
    """
    best = np.inf
    for _ in range(repeats):
        start = time.process_time()
        mech = load(str(FIXTURE))
        eq = mech.equilibrium()
        osc = small_oscillations(mech, eq)
        best = min(best, time.process_time() - start)
    phi, roots = closed_form()
    rocker = float(eq.q[mech.q_index("rocker")])
    return SpringFourBarResult(rocker, phi, osc.eigenvalues, roots, eq.residual, best)


def lines(r: SpringFourBarResult) -> list[str]:
    """The section's Markdown.

    Args:
        r: the measured result.

    Returns:
        Its lines.
    """
    s, exact = r.eigenvalues[-1], r.eigenvalues_exact[-1]
    angle = f"{PUBLISHED_PHI} ({abs(r.phi - PUBLISHED_PHI):.1e} from mechkit's)"
    return [
        "| quantity | mechkit | closed form | difference | published |",
        "|---|---|---|---|---|",
        f"| rocker angle phi (rad) | {r.phi:.12f} | {r.phi_exact:.12f} | {abs(r.phi - r.phi_exact):.1e} | {angle} |",
        f"| eigenvalues s (1/s) | {s.real:.10f} +- {s.imag:.10f} i | {exact.real:.10f} +- {exact.imag:.10f} i | "
        + f"{r.eigenvalue_error:.1e} relative | not found |",
        f"| CPU (load, equilibrium, eigenvalues) | {r.cpu:.3f} s | | | {PUBLISHED_SOLUTION} |",
        "",
        f"The equilibrium's reduced force is {r.residual:.1e} N m; natural frequency {abs(s) / (2 * np.pi):.6f} Hz, "
        + f"damping ratio {-s.real / abs(s):.6f}.",
    ]


def write_section(docs: Path) -> SpringFourBarResult:
    """Measure and write the section `HEADING` of docs/iftomm_benchmarks.md.

    Args:
        docs: the docs folder.

    Returns:
        The result written.
    """
    r = measure()
    text = "\n".join([HEADING, "", "This machine (CPU time of the fastest of 5 runs):", "", *lines(r)]) + "\n"
    replace_section(docs / "iftomm_benchmarks.md", HEADING, text)
    return r
