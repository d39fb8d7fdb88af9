"""A simulation's result: the motion study's arrays (inputs, efforts, every reaction) plus time, closure
residual, energies, works, friction power and events; its table form (Parquet, CSV) and its energy
balance.

Columns: those of `mechkit.history.MotionResult` (`t`, `q/`, `v/`, `a/`, `effort/<driven joint>`,
`reaction/<joint>/<component>`, `axis/<joint>/<x|y|z>`), then `closure_residual` (m),
`energy/kinetic`, `energy/gravity`, `energy/<element>` (potentials, J), `work/drives`,
`work/<element>` (non-conservative works, J), `dissipated/impacts` (J), `power/friction` (W) and
`energy/balance` (J). Metadata as the motion table's, plus the events and the integrator.

The energy balance: B = T + V_gravity + sum V_elements - W_drives - sum W_elements + D_impacts, with W
the works of the drives (their efforts times their rates, impulses included) and of each element's
non-conservative part (negative for dissipation), D the energy impacts took. B is constant for exact
dynamics; `energy_error` is its largest drift and `energy_scale` the largest change of any of its
terms over the run, the scale the drift is judged against.
"""

from __future__ import annotations

import io
import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from mechkit.base.atomic import write_bytes, write_text
from mechkit.history.result import MotionResult, pandas, pyarrow


@dataclass(frozen=True)
class SimulationResult:
    """A simulated motion, N samples (every accepted step).

    Attributes:
        motion: the motion-study arrays (`MotionResult`: q, v, a, efforts of the driven joints (NaN
            while a joint is not driven), reactions, axes).
        residual: (N,) largest closure residual (m for position rows).
        kinetic: (N,) kinetic energy (J).
        gravity: (N,) the model's gravity potential (J).
        element_names: the force elements.
        roles: their roles ("conservative", "dissipative", "source").
        potentials: (N, n_elements) each element's potential (J).
        works: (N, n_elements) each element's non-conservative work since the start (J).
        drive_work: (N,) the drives' work (J).
        impact_loss: (N,) energy taken by impacts (J).
        friction_power: (N,) power of the friction elements (W, <= 0).
        events: (t (s), event, what happened) in time order.
        integrator: how it was integrated (method, tolerances or step, steps, evaluations, dynamics and
            "dynamics_note": why the default changed, or "").
        momentum: on a free-flyer root, the whole system's momentum at each sample
            (`mechkit.bases.MomentumHistory`: conserved with no gravity and no external force); else None.
    """

    motion: MotionResult
    residual: np.ndarray
    kinetic: np.ndarray
    gravity: np.ndarray
    element_names: tuple[str, ...]
    roles: tuple[str, ...]
    potentials: np.ndarray
    works: np.ndarray
    drive_work: np.ndarray
    impact_loss: np.ndarray
    friction_power: np.ndarray
    events: tuple[tuple[float, str, str], ...] = ()
    integrator: dict = field(default_factory=dict)
    momentum: Any = None

    @property
    def t(self) -> np.ndarray:
        """(N,) times (s)."""
        return self.motion.t

    def column(self, joint: str) -> int:
        """The q (and v) column of a one-coordinate joint, by name.

        Args:
            joint: the joint.

        Returns:
            Its column in `motion.q` and `motion.v`.
        """
        return self.motion.coordinates.index(joint)

    @property
    def dissipated(self) -> np.ndarray:
        """(N,) energy dissipated since the start (J): minus the dissipative elements' work, plus impacts."""
        mask = np.array([r == "dissipative" for r in self.roles], dtype=bool)
        return -self.works[:, mask].sum(axis=1) + self.impact_loss

    @property
    def supplied(self) -> np.ndarray:
        """(N,) work supplied since the start (J): the drives' and the sources'."""
        mask = np.array([r == "source" for r in self.roles], dtype=bool)
        return self.drive_work + self.works[:, mask].sum(axis=1)

    @property
    def balance(self) -> np.ndarray:
        """(N,) T + V - supplied + dissipated (J): constant for exact dynamics."""
        return self.kinetic + self.gravity + self.potentials.sum(axis=1) - self.supplied + self.dissipated

    @property
    def energy_error(self) -> float:
        """Largest drift of the balance from its initial value (J)."""
        b = self.balance
        return float(np.max(np.abs(b - b[0])))

    @property
    def energy_scale(self) -> float:
        """Largest change over the run of any term of the balance (J)."""
        terms = [self.kinetic, self.gravity, *self.potentials.T, self.supplied, self.dissipated]
        return float(max(np.ptp(x) for x in terms))

    def summary(self) -> list[str]:
        """Lines for a person: samples, closure residual, the energy balance's terms and drift (on a
        free-flyer root the momentum's drift beside it), the dynamics where the root chose them."""
        T, V = self.kinetic, self.gravity + self.potentials.sum(axis=1)
        info = self.integrator
        lines = [
            (
                f"{len(self.t)} samples, t = {self.t[0]:.6g} .. {self.t[-1]:.6g} s, {info.get('method', '')} "
                f"{info.get('steps', '')} steps, {info.get('evaluations', '')} evaluations"
            ),
            f"closure residual: max {self.residual.max():.3g} m",
            (
                f"energy (J): kinetic {T[-1]:.6g}, potential {V[-1] - V[0]:+.6g} (change), "
                f"supplied {self.supplied[-1]:.6g}, dissipated {self.dissipated[-1]:.6g} "
                f"(impacts {self.impact_loss[-1]:.6g})"
            ),
            (
                f"energy balance: drift {self.energy_error:.3g} J of {self.energy_scale:.6g} J exchanged "
                f"({self.energy_error / max(self.energy_scale, 1e-300):.2g})"
            ),
        ]
        if self.momentum is not None:
            d = self.momentum.drift()
            lines.append(
                f"momentum drift: linear {d['linear']:.3g} kg m/s ({d['relative_linear']:.2g} of the bodies' "
                f"{self.momentum.scale:.3g}), angular {d['angular']:.3g} kg m^2/s, centre of mass {d['com']:.3g} m"
            )
        if info.get("dynamics_note"):
            lines.append(f"dynamics: {info['dynamics_note']}")
        lines += [f"t = {t:.6g} s: {name}: {what}" for t, name, what in self.events]
        return lines

    # ------------------------------------------------------------ table form
    def columns(self) -> dict[str, np.ndarray]:
        """Column name -> (N,) values: the motion table's, then the simulation's own."""
        cols = self.motion.columns()
        cols["closure_residual"] = self.residual
        cols["energy/kinetic"], cols["energy/gravity"] = self.kinetic, self.gravity
        for k, name in enumerate(self.element_names):
            cols[f"energy/{name}"] = self.potentials[:, k]
        cols["work/drives"] = self.drive_work
        for k, name in enumerate(self.element_names):
            cols[f"work/{name}"] = self.works[:, k]
        cols["dissipated/impacts"] = self.impact_loss
        cols["power/friction"] = self.friction_power
        cols["energy/balance"] = self.balance
        return cols

    def metadata(self) -> dict[str, str]:
        """The table's metadata (the motion table's, the elements, the events, the integrator)."""
        meta = self.motion.metadata()
        meta.update(
            {
                "elements": json.dumps(dict(zip(self.element_names, self.roles))),
                "events": json.dumps([list(e) for e in self.events]),
                "integrator": json.dumps(self.integrator, default=str),
            }
        )
        return meta

    def to_dataframe(self) -> Any:
        """A pandas DataFrame, one row per sample (metadata in `attrs`)."""
        df = pandas().DataFrame(self.columns())
        df.attrs.update(self.metadata())
        return df


def write_parquet(result: SimulationResult, path: str | Path) -> Path:
    """Write the table as Parquet (pyarrow), metadata in the schema; atomic.

    Args:
        result: the simulation.
        path: the file to write.

    Returns:
        The path written.
    """
    pyarrow()
    buffer = io.BytesIO()
    result.to_dataframe().to_parquet(buffer, engine="pyarrow", index=False)
    return write_bytes(path, buffer.getvalue())


def write_csv(result: SimulationResult, path: str | Path) -> Path:
    """Write the table as CSV (full precision), metadata as leading `# key: value` lines; atomic.

    Args:
        result: the simulation.
        path: the file to write.

    Returns:
        The path written.
    """
    header = "".join(f"# {k}: {v}\n" for k, v in result.metadata().items())
    return write_text(path, header + result.to_dataframe().to_csv(index=False))
