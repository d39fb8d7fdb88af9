"""The mechanism contract: everything mechkit reads about one registered mechanism, on one typed object.

A mechanism package (`mechkit/mechanisms/<name>/__init__.py`) declares one `MechanismSpec` named
`SPEC`; nothing else of the package is looked up by name, and no generic layer (bench, sweep,
motion, second opinion, viz, command line) imports a mechanism package: what they need of a
mechanism is one of the hooks below. Callbacks that receive the built mechanism take a
`mechkit.mechanism.Mechanism` (typed `Any` here: the contract sits below the `Mechanism` class in
the layering, so it cannot import it).

Hooks, by reader:

- `mechkit bench`: `bench_methods`, `bench_references` (the mechanism's own methods and the best
  independent reference per quantity), `bench_states` (its own motion to sample the bench's states
  along, where arbitrary inputs near home are not what its methods solve);
- the failure atlas (`mechkit bench --markdown`): `failure_studies`;
- motion studies and the motion-law bench: `motion_laws`;
- design sweeps: `design_metrics`;
- figures and the numbers the docs quote (`tools/figures.py NAME`): `studies`;
- pictures: `scenes`, `scene_times`, `view`, `caption`, `scene_captions`;
- `mechkit report`: `self_checks`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import Any

import numpy as np

from mechkit.base.exceptions import InvalidParameters, MechkitError
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
"""(Mechanism, bench sample) -> q (assembly), inputs (inverse kinematics), a (forward dynamics) or an
effort/reaction result (inverse dynamics)."""

CheckFunction = Callable[[Any], dict[str, float]]
"""Mechanism -> {check name: worst residual or relative error} (smaller is better)."""

BENCH_QUANTITIES = ("assembly", "inverse_kinematics", "forward_dynamics", "inverse_dynamics")
"""What `mechkit bench` measures: q from the inputs; the inputs from the rest of q (the papers' closed
forms: the core has no method of its own here); a from the efforts; efforts and reactions from (q, v, a)."""


@dataclass(frozen=True)
class BenchEntry:
    """A function of the mechanism's own for one bench quantity (`BenchMethod`, `BenchReference`).

    Attributes:
        label: the row's name in the benchmark tables.
        quantity: one of `BENCH_QUANTITIES`.
        fn: (mechanism, sample) -> q (nq,), the actuated inputs (rad or m, `actuated` order), a (nv,),
            or efforts (+ reactions) (see `mechkit.bench`).
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


@dataclass(frozen=True)
class MotionState:
    """One instant of a mechanism's own motion.

    Attributes:
        t: time, s.
        q: (nq,) configuration; v: (nv,) velocity; a: (nv,) acceleration (joint coordinates, SI).
    """

    t: float
    q: np.ndarray
    v: np.ndarray
    a: np.ndarray


BenchStates = Callable[[Any, int], Sequence[MotionState]]
"""(Mechanism, count) -> at least `count` + 1 states along the mechanism's own motion, in time order:
`mechkit bench` measures on `count` of them, each with the one before it as its warm start."""


@dataclass(frozen=True)
class FailureCase:
    """One method at one condition of a failure study.

    Attributes:
        study: the study's name.
        method: the method's label.
        condition: where along the study (its unit is the study's `condition` label).
        error: the method's error (finite), or nan when it did not return a result.
        outcome: "ok", "non-finite", "other branch", "root lost" or the exception's class name.
        message: the exception's message (shortened), if any.
    """

    study: str
    method: str
    condition: float
    error: float
    outcome: str
    message: str = ""

    @classmethod
    def attempt(cls, study: str, method: str, condition: float, error: Callable[[], float]) -> FailureCase:
        """A case from running `error()`: a finite error is "ok", a non-finite one "non-finite", a
        `MechkitError` its class name (the message kept).

        Args:
            study: the study's name.
            method: the method tried.
            condition: where it was tried (the study's condition axis).
            error: computes the method's error there.

        Returns:
            The case.
        """
        try:
            value = float(error())
        except MechkitError as err:
            return cls(study, method, condition, float("nan"), type(err).__name__, str(err)[:160])
        if not np.isfinite(value):
            return cls(study, method, condition, float("nan"), "non-finite")
        return cls(study, method, condition, value, "ok")


@dataclass(frozen=True)
class FailureStudy:
    """A study of the failure atlas declared by a mechanism: where its own methods fail, and how.

    Attributes:
        name: the study's name (its figure is `bench_atlas_<name>`).
        run: (mechanism, quick) -> the cases (quick: the fewer conditions of `mechkit bench --quick`).
        condition: the x axis: what the condition is, with its unit.
        error: the y axis: what the error is, with its unit.
        log_condition: the condition axis is logarithmic.
        towards_zero: the condition approaches a failure at 0 (axis drawn right to left; a condition
            of 0 and a negative one, past the failure, are drawn left of the data).
        counts: drawn as the count of each outcome per method (the condition is a trial index).
        note: a line written on the figure.
    """

    name: str
    run: Callable[[Any, bool], list[FailureCase]]
    condition: str
    error: str
    log_condition: bool = True
    towards_zero: bool = False
    counts: bool = False
    note: str = ""


@dataclass(frozen=True)
class SampledLaw:
    """An input law sampled at increasing times.

    Attributes:
        joints: the driven joints, in column order.
        t: (N,) times, s.
        values: (N, k) joint coordinates (rad or m).
        rates, accelerations: (N, k) their derivatives, or None for those of a spline through `values`.
        guesses: (N, nq) configurations near the samples (warm starts), or None.
        source: one line naming the law, for reports.
    """

    joints: tuple[str, ...]
    t: np.ndarray
    values: np.ndarray
    rates: np.ndarray | None = None
    accelerations: np.ndarray | None = None
    guesses: np.ndarray | None = None
    source: str = ""


@dataclass(frozen=True)
class MotionLaw:
    """A motion of the mechanism's own (a paper's law, a simulated deployment) for motion studies.

    Attributes:
        sample: (mechanism, samples or None for the law's own count) -> the `SampledLaw`.
        reactions: the joints whose reactions a plot of the law shows (empty: the busiest).
    """

    sample: Callable[[Any, int | None], SampledLaw]
    reactions: tuple[str, ...] = ()


@dataclass(frozen=True)
class DesignMetric:
    """A figure of merit of one design, from the built mechanism alone (no motion study), for sweeps.

    Attributes:
        name: the metric's name (`mechkit sweep --metric NAME`).
        unit: the unit of its columns.
        doc: one line saying what it is.
        columns: the column names `fn` fills.
        fn: mechanism -> {column: value}.
    """

    name: str
    unit: str
    doc: str
    columns: tuple[str, ...]
    fn: Callable[[Any], dict[str, float]]


@dataclass(frozen=True)
class MechanismStudy:
    """A study of the mechanism's own that returns data: the figures and numbers its docs page quotes.

    Attributes:
        doc: one line saying what it shows.
        run: mechanism -> the study's data (at the sizes the docs quote).
        lines: data -> the numbers, as text lines (printed by `tools/figures.py`).
        figures: (data, folder) -> the figure files written (matplotlib), or None for none.
    """

    doc: str
    run: Callable[[Any], Any]
    lines: Callable[[Any], list[str]]
    figures: Callable[[Any, Path], list[Path]] | None = None


def _frozen(mapping: Mapping[str, Any]) -> Mapping[str, Any]:
    return MappingProxyType(dict(mapping))


@dataclass(frozen=True)
class MechanismSpec:
    """What mechkit knows about one mechanism besides its xacro template.

    Attributes:
        name: registry name (also the stem of `xacro/<name>.urdf.xacro`, `urdf/<name>.urdf` and
            `docs/mechanisms/<name>.md`).
        params: the frozen parameter dataclass; every field is a xacro argument of the template.
        template: template file name in the packaged `xacro/` folder.
        actuated: URDF joint names carrying actuators, or a function of the parameters giving them.
        gruebler_dof: the Gruebler-Kutzbach mobility count, compared with the numerical one.
        home: parameters -> inputs (joint name -> rad or m) of the default assembly.
        guess: parameters -> initial guess (joint name -> value) picking the assembly branch.
        pose: what `guess` is, named by the assembly's branch (a file's "the keyframe 'home'"; default:
            "the spec's guess").
        summary: one line for `mechkit list` (must equal the registry entry's summary).
        caption: a few words for the gallery (default: the summary).
        scenes: scene name -> function giving assembled poses (`mechkit snapshot --scene`, gallery).
        scene_times: scene name -> the times of its poses, for the scenes that follow a law in time
            (motion studies differentiate the inputs along them; other scenes get uniform steps).
        scene_captions: scene name -> what its pictures show, in a few words (the gallery).
        view: camera direction (world frame, from the target towards the camera), or None for the
            automatic choice (face-on to planar linkages, oblique otherwise).
        bench_methods: the mechanism's own methods (the paper's closed forms, its SOC decomposition).
        bench_references: at most one reference per bench quantity, independent of the core.
        bench_states: the mechanism's own motion the bench samples its states along, or None for
            inputs drawn near home.
        failure_studies: the failure atlas's studies of the mechanism's own methods.
        motion_laws: law name -> a motion of the mechanism's own (motion studies, the motion bench).
        design_metrics: figures of merit a sweep can ask of a design; when there are any, a sweep's
            default metrics are "assembles", "branch" and these.
        studies: study name -> a study returning data (figures and the docs' numbers).
        self_checks: extra `mechkit report` checks: mechanism -> {check name: worst error}.
    """

    name: str
    params: type[MechanismParams]
    template: str
    actuated: tuple[str, ...] | Callable[[Any], tuple[str, ...]]
    gruebler_dof: int
    home: Callable[[Any], Inputs]
    guess: Callable[[Any], Inputs] | None = None
    pose: str = ""
    summary: str = ""
    caption: str = ""
    scenes: Mapping[str, SceneFunction] = field(default_factory=dict)
    scene_times: Mapping[str, SceneTimes] = field(default_factory=dict)
    scene_captions: Mapping[str, str] = field(default_factory=dict)
    view: tuple[float, float, float] | None = None
    bench_methods: tuple[BenchMethod, ...] = ()
    bench_references: tuple[BenchReference, ...] = ()
    bench_states: BenchStates | None = None
    failure_studies: tuple[FailureStudy, ...] = ()
    motion_laws: Mapping[str, MotionLaw] = field(default_factory=dict)
    design_metrics: tuple[DesignMetric, ...] = ()
    studies: Mapping[str, MechanismStudy] = field(default_factory=dict)
    self_checks: CheckFunction | None = None

    def __post_init__(self) -> None:
        for name in ("scenes", "scene_times", "scene_captions", "motion_laws", "studies"):
            object.__setattr__(self, name, _frozen(getattr(self, name)))
        for name in ("scene_times", "scene_captions"):
            if not set(getattr(self, name)) <= set(self.scenes):
                raise InvalidParameters(name, sorted(getattr(self, name)), f"{self.name}: undeclared scenes")
        for name in ("bench_methods", "bench_references", "failure_studies", "design_metrics"):
            object.__setattr__(self, name, tuple(getattr(self, name)))
        quantities = [r.quantity for r in self.bench_references]
        if len(set(quantities)) != len(quantities):
            raise InvalidParameters("bench_references", quantities, f"{self.name}: one reference per quantity")
        for name, labels in (
            ("failure_studies", [s.name for s in self.failure_studies]),
            ("design_metrics", [m.name for m in self.design_metrics]),
        ):
            if len(set(labels)) != len(labels):
                raise InvalidParameters(name, labels, f"{self.name}: names must be unique")
        if self.view is not None:
            view = tuple(float(c) for c in self.view)
            if len(view) != 3 or not np.any(view):
                raise InvalidParameters("view", self.view, f"{self.name}: a non-zero 3-vector")
            object.__setattr__(self, "view", view)

    def actuated_joints(self, params: MechanismParams) -> tuple[str, ...]:
        """The actuated joint names at these parameters.

        Args:
            params: the mechanism's parameters.

        Returns:
            The actuated joint names.
        """
        return tuple(self.actuated(params) if callable(self.actuated) else self.actuated)

    @property
    def template_path(self) -> Path:
        """The template file inside the packaged `xacro/` folder."""
        return xacro_dir() / self.template

    def default_urdf(self) -> str:
        """The URDF generated at the default parameters (what the packaged `urdf/<name>.urdf` holds)."""
        return render_urdf(self.template_path, self.params().xacro_args())

    def reference(self, quantity: str) -> BenchReference | None:
        """The mechanism's own reference for a bench quantity, if it has one.

        Args:
            quantity: a bench quantity (`BENCH_QUANTITIES`).

        Returns:
            The reference, or None (the bench then uses the core's).
        """
        return next((r for r in self.bench_references if r.quantity == quantity), None)
