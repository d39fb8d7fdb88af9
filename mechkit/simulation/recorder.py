"""The samples of a simulation as it runs: every accepted step's state, its evaluation, its energies, and
the events; the reactions of all samples after the run, batched by the set of driven joints."""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit import core
from mechkit.simulation.projection import Projection
from mechkit.simulation.state_layout import StateLayout
from mechkit.simulation.system import MechanismSystem


class Recorder:
    """Collects the samples of one run.

    Args:
        system: the equations of motion (its drives change when joints are held or released).
        layout: the integrated vector's layout.
        projection: for the closure residual of each sample.

    Attributes:
        effort_names: every joint driven at some time, in order of appearance (the effort columns).
        events: (t, event, what happened).
        steps: accepted steps.
        evaluations: evaluations of the equations of motion.
    """

    def __init__(self, system: MechanismSystem, layout: StateLayout, projection: Projection):
        self.system, self.layout, self.projection = system, layout, projection
        self.effort_names: list[str] = list(system.drives.all)
        self.events: list[tuple[float, str, str]] = []
        self.steps = self.evaluations = 0
        self._drive_impulses = self._impact_loss = 0.0
        self._rows: dict[str, list] = {
            k: []
            for k in (
                "t",
                "q",
                "v",
                "a",
                "efforts",
                "generalized",
                "wrenches",
                "powers",
                "works",
                "residual",
                "kinetic",
                "gravity",
                "potentials",
                "drive_work",
                "impact_loss",
                "driven",
            )
        }

    def impulse(self, drive_work: float, dissipated: float) -> None:
        """Add an impact's energies.

        Args:
            drive_work: the drives' impulsive work (J).
            dissipated: the energy the impact dissipated (J).
        """
        self._drive_impulses += drive_work
        self._impact_loss += dissipated

    def holding(self, joint: str) -> None:
        """A joint is now driven (held): it gets an effort column.

        Args:
            joint: the joint.
        """
        if joint not in self.effort_names:
            self.effort_names.append(joint)

    def event(self, t: float, name: str, what: str) -> None:
        """Log an event.

        Args:
            t: its time (s).
            name: the event (e.g. "upper:joint").
            what: what happened.
        """
        self.events.append((float(t), name, what))

    def record(self, t: float, y: np.ndarray, cache: dict) -> None:
        """Record one sample, with the evaluation the integrator made there (or a new one).

        Args:
            t: the time (s).
            y: the integrated vector at t.
            cache: the integrator's last evaluation ("t", "y", "ev": an `Evaluation`), used when it
                was made at (t, y).
        """
        s, L = self.system, self.layout
        q, v = L.q(y), L.v(y).copy()
        if cache.get("t") == t and np.array_equal(cache.get("y"), y):
            ev = cache["ev"]
        else:
            ev = s.evaluate(t, q, v)
            self.evaluations += 1
        rows = self._rows
        efforts = np.full(len(self.effort_names), np.nan)
        for name, u in zip(s.drives.all, ev.efforts):
            efforts[self.effort_names.index(name)] = u
        works = L.works(y)
        potentials = s.potentials(q)
        for key, value in (
            ("t", t),
            ("q", q),
            ("v", v),
            ("a", ev.a),
            ("efforts", efforts),
            ("generalized", ev.generalized),
            ("wrenches", ev.wrenches),
            ("powers", ev.powers),
            ("works", works[1:]),
            ("residual", self.projection.residual(q)),
            ("kinetic", s.kinetic(q, v)),
            ("gravity", potentials[0]),
            ("potentials", potentials[1:]),
            ("drive_work", works[0] + self._drive_impulses),
            ("impact_loss", self._impact_loss),
            ("driven", s.drives.all),
        ):
            rows[key].append(value)

    def arrays(self) -> dict[str, np.ndarray]:
        """The samples as arrays (efforts padded with NaN to every effort column)."""
        out = {k: np.array(v) for k, v in self._rows.items() if k not in ("efforts", "driven")}
        width = len(self.effort_names)
        out["efforts"] = np.array(
            [np.pad(e, (0, width - len(e)), constant_values=np.nan) for e in self._rows["efforts"]]
        )
        out["efforts"] = out["efforts"].reshape(len(out["t"]), width)
        n = len(out["t"])
        for key, size in (
            ("powers", self.system.elements),
            ("works", self.system.elements),
            ("potentials", self.system.elements),
        ):
            out[key] = out[key].reshape(n, len(size))
        return out

    def groups(self) -> dict[tuple[str, ...], np.ndarray]:
        """Driven joints -> the samples driven by exactly those."""
        out: dict[tuple[str, ...], list[int]] = {}
        for i, names in enumerate(self._rows["driven"]):
            out.setdefault(names, []).append(i)
        return {k: np.array(v, dtype=int) for k, v in out.items()}

    def system_reactions(self, driven: core.ClosureModel, rows: np.ndarray, r: dict) -> core.BatchInverseDynamicsResult:
        """The core's inverse dynamics of some samples, the elements' generalised forces passive and their
        wrenches external.

        Args:
            driven: the closure model with the samples' driven joints as its actuation.
            rows: (n,) indices of the samples.
            r: the samples' arrays (`arrays`).

        Returns:
            The core's batch result: efforts (n, k) of the driven joints and reactions (n, n_joints, 6).
        """
        fexts = []
        for i in rows:
            f = pin.StdVec_Force()
            for w in r["wrenches"][i]:
                f.append(pin.Force(w[:3].copy(), w[3:].copy()))
            fexts.append(f)
        return core.inverse_dynamics_batch(
            driven,
            driven.create_data(),
            r["q"][rows],
            r["v"][rows],
            r["a"][rows],
            fexts,
            r["generalized"][rows],
            determinacy_test=False,
        )
