"""The mechanism contract: everything mechkit reads about one registered mechanism, on one typed object.

A mechanism package (`mechkit/mechanisms/<name>/__init__.py`) declares one `MechanismSpec` named
`SPEC`; nothing else of the package is looked up by name. Callbacks that receive the built
mechanism take a `mechkit.mechanism.Mechanism` (typed `Any` here: the contract sits below the
`Mechanism` class in the layering, so it cannot import it).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import Any

import numpy as np

from mechkit.base.exceptions import InvalidParameters
from mechkit.base.resources import xacro_dir
from mechkit.catalog.params import MechanismParams
from mechkit.sources.xacro_file import render_urdf

Inputs = Mapping[str, float]
"""Joint name -> coordinate (rad or m)."""

SceneFunction = Callable[[Any], Sequence[np.ndarray]]
"""Mechanism -> assembled configurations q (nq,), in order (an animation or an overlay)."""

SceneTimes = Callable[[Any, int], np.ndarray]
"""(Mechanism, number of poses) -> the times (s) of a time-parametrised scene's poses."""

BenchFunction = Callable[[Any, Any], Any]
"""(Mechanism, bench sample) -> q (assembly), a (forward dynamics) or an effort/reaction result."""

CheckFunction = Callable[[Any], dict[str, float]]
"""Mechanism -> {check name: worst residual or relative error} (smaller is better)."""

BENCH_QUANTITIES = ("assembly", "forward_dynamics", "inverse_dynamics")


@dataclass(frozen=True)
class BenchEntry:
    """A function of the mechanism's own for one bench quantity (`BenchMethod`, `BenchReference`).

    Attributes:
        label: the row's name in the benchmark tables.
        quantity: one of `BENCH_QUANTITIES`.
        fn: (mechanism, sample) -> q (nq,), a (nv,), or efforts (+ reactions) (see `mechkit.bench`).
    """

    label: str
    quantity: str
    fn: BenchFunction

    def __post_init__(self) -> None:
        if self.quantity not in BENCH_QUANTITIES:
            raise InvalidParameters("quantity", self.quantity, f"bench quantities are {', '.join(BENCH_QUANTITIES)}")


@dataclass(frozen=True)
class BenchMethod(BenchEntry):
    """One of the mechanism's own methods, timed beside the core's in `mechkit bench`."""


@dataclass(frozen=True)
class BenchReference(BenchEntry):
    """The best independent reference the mechanism has for one bench quantity (the table's `reference`)."""


def _frozen(mapping: Mapping[str, Any]) -> Mapping[str, Any]:
    return MappingProxyType(dict(mapping))


@dataclass(frozen=True)
class MechanismSpec:
    """What mechkit knows about one mechanism besides its xacro template.

    Attributes:
        name: registry name (also the stem of `xacro/<name>.urdf.xacro` and `urdf/<name>.urdf`).
        params: the frozen parameter dataclass; every field is a xacro argument of the template.
        template: template file name in the packaged `xacro/` folder.
        actuated: URDF joint names carrying actuators, or a function of the parameters giving them.
        gruebler_dof: the Gruebler-Kutzbach mobility count, compared with the numerical one.
        home: parameters -> inputs (joint name -> rad or m) of the default assembly.
        guess: parameters -> initial guess (joint name -> value) picking the assembly branch.
        summary: one line for `mechkit list` (must equal the registry entry's summary).
        scenes: scene name -> function giving assembled poses (`mechkit snapshot --scene`, gallery).
        scene_times: scene name -> the times of its poses, for the scenes that follow a law in time
            (motion studies differentiate the inputs along them; other scenes get uniform steps).
        view: camera direction (world frame, from the target towards the camera), or None for the
            automatic choice (face-on to planar linkages, oblique otherwise).
        bench_methods: the mechanism's own methods (the paper's closed forms, its SOC decomposition).
        bench_references: at most one reference per bench quantity, independent of the core.
        self_checks: extra `mechkit report` checks: mechanism -> {check name: worst error}.
    """

    name: str
    params: type[MechanismParams]
    template: str
    actuated: tuple[str, ...] | Callable[[Any], tuple[str, ...]]
    gruebler_dof: int
    home: Callable[[Any], Inputs]
    guess: Callable[[Any], Inputs] | None = None
    summary: str = ""
    scenes: Mapping[str, SceneFunction] = field(default_factory=dict)
    scene_times: Mapping[str, SceneTimes] = field(default_factory=dict)
    view: tuple[float, float, float] | None = None
    bench_methods: tuple[BenchMethod, ...] = ()
    bench_references: tuple[BenchReference, ...] = ()
    self_checks: CheckFunction | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "scenes", _frozen(self.scenes))
        object.__setattr__(self, "scene_times", _frozen(self.scene_times))
        if not set(self.scene_times) <= set(self.scenes):
            raise InvalidParameters("scene_times", sorted(self.scene_times), f"{self.name}: times of undeclared scenes")
        object.__setattr__(self, "bench_methods", tuple(self.bench_methods))
        object.__setattr__(self, "bench_references", tuple(self.bench_references))
        quantities = [r.quantity for r in self.bench_references]
        if len(set(quantities)) != len(quantities):
            raise InvalidParameters("bench_references", quantities, f"{self.name}: one reference per quantity")
        if self.view is not None:
            view = tuple(float(c) for c in self.view)
            if len(view) != 3 or not np.any(view):
                raise InvalidParameters("view", self.view, f"{self.name}: a non-zero 3-vector")
            object.__setattr__(self, "view", view)

    def actuated_joints(self, params: MechanismParams) -> tuple[str, ...]:
        """The actuated joint names at these parameters."""
        return tuple(self.actuated(params) if callable(self.actuated) else self.actuated)

    @property
    def template_path(self) -> Path:
        """The template file inside the packaged `xacro/` folder."""
        return xacro_dir() / self.template

    def default_urdf(self) -> str:
        """The URDF generated at the default parameters (what the packaged `urdf/<name>.urdf` holds)."""
        return render_urdf(self.template_path, self.params().xacro_args())

    def reference(self, quantity: str) -> BenchReference | None:
        """The mechanism's own reference for a bench quantity, if it has one."""
        return next((r for r in self.bench_references if r.quantity == quantity), None)
