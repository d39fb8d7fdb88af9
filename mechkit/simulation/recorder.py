"""The samples of a simulation as it runs: every accepted step's state, its evaluation, its energies, and
the events; the reactions of all samples after the run, batched by the set of driven joints."""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from mechkit import core
from mechkit.simulation.projection import Projection
from mechkit.simulation.state_layout import StateLayout
from mechkit.simulation.system import Evaluation, MechanismSystem

#: Samples the recorder's arrays hold at first (doubled whenever they fill).
CAPACITY = 1024


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
        model, n = system.model, len(system.elements)
        widths = {
            "t": (),
            "q": (model.nq,),
            "v": (model.nv,),
            "a": (model.nv,),
            "generalized": (model.nv,),
            "wrenches": (model.njoints, 6),
            "powers": (n,),
            "works": (n,),
            "residual": (),
            "kinetic": (),
            "gravity": (),
            "potentials": (n,),
            "drive_work": (),
            "impact_loss": (),
        }
        self._arrays = {k: np.empty((CAPACITY, *w)) for k, w in widths.items()}  # doubled when full
        self._size = 0
        self._efforts: list[tuple[tuple[str, ...], np.ndarray]] = []  # (driven joints, their efforts) per sample

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

    def keep(self, cache: dict, t: float, y: np.ndarray, ev: Evaluation) -> None:
        """Keep an evaluation in the cache, with what it was made under (the method and the drives).

        Args:
            cache: the cache (a dict, written).
            t: the time (s).
            y: the integrated vector it was made at.
            ev: the evaluation.
        """
        cache["t"], cache["y"], cache["ev"] = t, y.copy(), ev
        cache["under"] = (self.system.method, self.system.drives)

    def cached(self, cache: dict, t: float, y: np.ndarray) -> bool:
        """Whether the cache holds the evaluation at (t, y) under the present method and drives.

        Args:
            cache: the cache (`keep`).
            t: the time (s).
            y: the integrated vector.

        Returns:
            True where it can be used.
        """
        under = cache.get("under")
        return (
            cache.get("t") == t
            and under[0] == self.system.method
            and under[1] is self.system.drives
            and np.array_equal(cache["y"], y)
        )

    def record(self, t: float, y: np.ndarray, cache: dict) -> None:
        """Record one sample, with the evaluation the integrator made there (or a new one).

        Args:
            t: the time (s).
            y: the integrated vector at t.
            cache: the last evaluation (`keep`), used when it was made at (t, y) under the present method
                and drives; the sample's own is kept there (a fixed step's first stage).
        """
        s, L = self.system, self.layout
        q, v = L.q(y), L.v(y).copy()
        if self.cached(cache, t, y):
            ev = cache["ev"]
        else:
            ev = s.evaluate(t, q, v)
            self.keep(cache, t, y, ev)
            self.evaluations += 1
        if self._size == len(self._arrays["t"]):
            self._arrays = {k: np.concatenate([x, np.empty_like(x)]) for k, x in self._arrays.items()}
        i, out = self._size, self._arrays
        works = L.works(y)
        potentials = s.potentials(q)
        out["t"][i], out["q"][i], out["v"][i], out["a"][i] = t, q, v, ev.a
        out["generalized"][i], out["wrenches"][i], out["powers"][i] = ev.generalized, ev.wrenches, ev.powers
        out["works"][i], out["residual"][i], out["kinetic"][i] = works[1:], self.projection.residual(q), s.kinetic(q, v)
        out["gravity"][i], out["potentials"][i] = potentials[0], potentials[1:]
        out["drive_work"][i], out["impact_loss"][i] = works[0] + self._drive_impulses, self._impact_loss
        self._efforts.append((s.drives.all, np.array(ev.efforts)))
        self._size += 1

    def arrays(self) -> dict[str, np.ndarray]:
        """The samples as arrays (efforts padded with NaN to every effort column)."""
        n = self._size
        out = {k: x[:n].copy() for k, x in self._arrays.items()}
        efforts = np.full((n, len(self.effort_names)), np.nan)
        for i, (names, values) in enumerate(self._efforts):
            efforts[i, [self.effort_names.index(name) for name in names]] = values
        out["efforts"] = efforts
        return out

    def groups(self) -> dict[tuple[str, ...], np.ndarray]:
        """Driven joints -> the samples driven by exactly those."""
        out: dict[tuple[str, ...], list[int]] = {}
        for i, (names, _) in enumerate(self._efforts):
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
