"""What a sweep measures on each design: the motion study every design runs, and the metrics, each
defined once with its unit.

The motion study (`Study`) drives the actuated inputs along a law over `samples` instants of one
period: "swing" (each input home + amplitude sin(2 pi t / T), all together), "turn" (each revolute
input one full turn at constant speed from home) or a scene of the mechanism (its poses spaced
evenly in time over the period; input rates and accelerations by central differences of the input
coordinates, periodic ends for "turn"-like closed scenes are not assumed: one-sided at the ends).
`motion_samples` assembles each instant from the previous one, projects the input rates and
accelerations with `Mechanism.velocities/accelerations` and solves `Mechanism.inverse_dynamics`
(the place where `mechkit.motion` could take over once it lands).

A metric maps (mechanism, samples) to named columns; names with a joint are `metric.joint`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import ClosureNotConverged, InvalidParameters, SingularConfiguration
from mechkit.mechanism import Mechanism
from mechkit.scenes import scene_poses

LAWS = ("swing", "turn")
SINGULAR_INV_COND = 1e-6  # inverse condition of the passive block below which a pose counts as singular (ours)


@dataclass(frozen=True)
class Study:
    """The motion each design runs.

    Attributes:
        law: "swing" or "turn" (ignored when `scene` is set).
        samples: instants along the motion.
        period: duration of the motion (s).
        amplitude: swing amplitude (rad for revolute inputs, m for prismatic ones).
        scene: a scene name of the mechanism whose poses are the motion, or None.
    """

    law: str = "swing"
    samples: int = 100
    period: float = 1.0
    amplitude: float = 0.3
    scene: str | None = None

    def __post_init__(self) -> None:
        if self.scene is None and self.law not in LAWS:
            raise InvalidParameters("law", self.law, f"one of {', '.join(LAWS)}")
        if self.samples < 2:
            raise InvalidParameters("samples", self.samples, "a motion needs at least 2 samples")
        if not (math.isfinite(self.period) and self.period > 0):
            raise InvalidParameters("period", self.period, "must be a finite duration > 0 (s)")
        if not math.isfinite(self.amplitude):
            raise InvalidParameters("amplitude", self.amplitude, "must be finite (rad or m)")


@dataclass(frozen=True)
class Samples:
    """A design's motion study, sample by sample (n samples).

    Attributes:
        t: (n,) time, s.
        q: (n, nq) assembled configurations.
        efforts: (n, actuators) actuator efforts, N m (revolute) or N (prismatic).
        forces, moments: (n, joints) norms of each joint's reaction force (N) and moment (N m,
            about the joint origin), in `joints` order (tree joints, then cut joints).
        joints: the joint names of `forces` and `moments`.
        inv_cond: (n,) inverse condition number of the passive block (0: singular).
        residual: (n,) largest closure residual (m, or rad-like for alignment rows).
    """

    t: np.ndarray
    q: np.ndarray
    efforts: np.ndarray
    forces: np.ndarray
    moments: np.ndarray
    joints: tuple[str, ...]
    inv_cond: np.ndarray
    residual: np.ndarray


class SingularAlongMotion(SingularConfiguration):
    """The motion reached a pose where the inputs do not determine the motion (or left the workspace)."""


def input_law(mech: Mechanism, study: Study) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The actuated inputs along the study's law: a full turn ("turn") or a sine about home.

    Args:
        mech: the mechanism.
        study: the motion study (law, samples, period, amplitude or scene).

    Returns:
        (t (n,) s, inputs (n, actuators) rad or m, rates (n, actuators), accelerations (n, actuators)).
    """
    n, T = study.samples, study.period
    t = np.arange(n) * T / n
    home = np.array([mech.home_q[mech.q_index(j)] for j in mech.actuated])
    w = 2 * math.pi / T
    if study.law == "turn":
        ones = np.ones(len(home))
        return t, home + np.outer(w * t, ones), np.outer(np.full(n, w), ones), np.zeros((n, len(home)))
    s, c = np.sin(w * t)[:, None], np.cos(w * t)[:, None]
    A = study.amplitude
    return t, home + A * s * np.ones(len(home)), A * w * c * np.ones(len(home)), -A * w**2 * s * np.ones(len(home))


def scene_law(mech: Mechanism, study: Study) -> tuple[np.ndarray, list[np.ndarray], np.ndarray, np.ndarray, np.ndarray]:
    """A scene spaced evenly over the study's period, its input rates and accelerations by finite differences.

    Args:
        mech: the mechanism.
        study: the motion study (law, samples, period, amplitude or scene).

    Returns:
        (t (n,) s, poses [(nq,)], inputs (n, actuators), rates, accelerations).
    """
    poses = scene_poses(mech, study.scene)
    t = np.linspace(0.0, study.period, len(poses))
    x = np.array([[q[mech.q_index(j)] for j in mech.actuated] for q in poses])
    rates = np.gradient(x, t, axis=0)
    return t, poses, x, rates, np.gradient(rates, t, axis=0)


def motion_samples(mech: Mechanism, study: Study) -> Samples:
    """Assemble, project and solve the inverse dynamics at every instant of the study.

    Args:
        mech: the mechanism.
        study: the motion study (law, samples, period, amplitude or scene).

    Returns:
        Per instant: q, efforts, reaction force and moment magnitudes, the passive block's inverse condition, the
            closure residual.

    Raises:
        SingularAlongMotion: (a SingularConfiguration) a pose does not assemble from the previous one, or the
            passive block is singular there (inverse condition below `SINGULAR_INV_COND`).
    """
    if study.scene is None:
        t, x, xd, xdd = input_law(mech, study)
        poses = None
    else:
        t, poses, x, xd, xdd = scene_law(mech, study)
    n = len(t)
    q_prev = mech.home_q
    qs, efforts, forces, moments, inv_cond, residual = [], [], [], [], [], []
    joints: tuple[str, ...] = ()
    for k in range(n):
        try:
            q = poses[k] if poses is not None else mech.assemble(x[k], guess=q_prev, tol=1e-10)
            cond = mech.singularity(q)
            if not 1.0 / cond > SINGULAR_INV_COND:
                raise SingularConfiguration(cond, "passive block of the closure Jacobian")
            v = mech.velocities(q, xd[k])
            a = mech.accelerations(q, v, xdd[k])
            result = mech.inverse_dynamics(q, v, a, determinacy=False)
        except SingularConfiguration as err:
            raise SingularAlongMotion(
                getattr(err, "cond", float("inf")), f"sample {k} (t = {t[k]:.4g} s): {err}"
            ) from None
        except ClosureNotConverged as err:  # after home: the motion left the workspace
            raise SingularAlongMotion(
                float("inf"),
                f"sample {k} (t = {t[k]:.4g} s) does not assemble from the "
                f"previous pose (a dead point or the workspace's edge): {err}",
            ) from None
        joints = tuple(result.reactions)
        qs.append(q)
        efforts.append([result.efforts[j] for j in mech.actuated])
        forces.append([np.linalg.norm(r.wrench[:3]) for r in result.reactions.values()])
        moments.append([np.linalg.norm(r.wrench[3:]) for r in result.reactions.values()])
        inv_cond.append(1.0 / cond)
        residual.append(float(np.max(np.abs(mech.closure_residual(q)), initial=0.0)))
        q_prev = q
    return Samples(
        t,
        np.array(qs),
        np.array(efforts),
        np.array(forces),
        np.array(moments),
        joints,
        np.array(inv_cond),
        np.array(residual),
    )


@dataclass(frozen=True)
class Metric:
    """One measured quantity.

    Attributes:
        name: the metric's name (`--metric NAME`); a per-joint metric's columns are `name.joint`.
        unit: its unit.
        doc: one line saying what it is.
        columns: mechanism -> the column names it fills.
        fn: (mechanism, samples or None) -> {column: value}.
        motion: True when it needs the motion study (`samples`).
    """

    name: str
    unit: str
    doc: str
    columns: Callable[[Mechanism], list[str]]
    fn: Callable[[Mechanism, Samples | None], dict[str, float]]
    motion: bool = True


def _per(name: str, names: Callable[[Mechanism], tuple[str, ...]]) -> Callable[[Mechanism], list[str]]:
    return lambda mech: [f"{name}.{j}" for j in names(mech)]


def joint_names(mech: Mechanism) -> tuple[str, ...]:
    """The joints whose reactions `inverse_dynamics` reports (tree joints, then cut joints).

    Args:
        mech: the mechanism.

    Returns:
        Joint names.
    """
    zero = np.zeros(mech.model.nv)
    return tuple(mech.inverse_dynamics(mech.home_q, zero, zero, determinacy=False).reactions)


def _peaks(name: str, values: Callable[[Samples], np.ndarray], names: Callable[[Mechanism], tuple[str, ...]]):
    def fn(mech: Mechanism, s: Samples) -> dict[str, float]:
        return dict(zip(_per(name, names)(mech), np.max(np.abs(values(s)), axis=0).tolist()))

    return fn


def _branch(mech: Mechanism, _: Samples | None) -> dict[str, float]:
    """Sign of the determinant of the passive block at home (square blocks), else 0."""
    free = np.setdiff1d(np.arange(mech.model.nv), [mech.v_index(j) for j in mech.actuated])
    block = mech.closure_jacobian(mech.home_q)[:, free]
    if block.shape[0] != block.shape[1]:
        return {"branch": 0.0}
    return {"branch": float(np.sign(np.linalg.det(block)))}


def _elastic(mech: Mechanism):
    """The mechanism's elastic model (sections from its description), and its heaviest moving body's link."""
    from mechkit.elastic import ElasticModel

    elastic = ElasticModel(mech)
    heaviest = max(range(1, mech.model.njoints), key=lambda j: mech.model.inertias[j].mass)
    link = next(name for name, frame in elastic.links.items() if frame.parentJoint == heaviest)
    return elastic, link


def _first_frequency(mech: Mechanism) -> float:
    """The first natural frequency (Hz) at home, actuators locked (nan where every mode is held rigidly: the
    design is then "failed"; `MethodUnavailable` where nothing is elastic)."""
    elastic, _ = _elastic(mech)
    frequencies = elastic.modes(mech.home_q, 1).frequencies
    return float(frequencies[0]) if len(frequencies) else float("nan")


def _stiffness(mech: Mechanism, _: Samples | None) -> dict[str, float]:
    """1 / C_ii of the heaviest moving body at its centre of mass, home pose (every other direction free)."""
    elastic, link = _elastic(mech)
    body = elastic.body(link)
    s = elastic.stiffness(mech.home_q, link, mech.model.inertias[body].lever)
    return dict(zip(STIFFNESS_COLUMNS, s.free.tolist()))


def _mass(mech: Mechanism) -> float:
    """Total mass of the bodies (kg)."""
    return float(sum(inertia.mass for inertia in mech.model.inertias))


STIFFNESS_COLUMNS = tuple(f"stiffness.{d}" for d in ("x", "y", "z", "rx", "ry", "rz"))

GENERIC = (
    Metric(
        "assembles",
        "-",
        "1 when the design assembles at its home inputs (failed designs: status)",
        lambda m: ["assembles"],
        lambda m, s: {"assembles": 1.0},
        motion=False,
    ),
    Metric(
        "branch",
        "-",
        "assembly branch at home: sign of det of the passive block of the closure Jacobian (0 when not square)",
        lambda m: ["branch"],
        _branch,
        motion=False,
    ),
    Metric(
        "peak_effort",
        "N m or N",
        "largest |effort| of each actuator along the motion",
        _per("peak_effort", lambda m: m.actuated),
        _peaks("peak_effort", lambda s: s.efforts, lambda m: m.actuated),
    ),
    Metric(
        "peak_force",
        "N",
        "largest reaction force norm of each joint along the motion",
        _per("peak_force", joint_names),
        _peaks("peak_force", lambda s: s.forces, joint_names),
    ),
    Metric(
        "peak_moment",
        "N m",
        "largest reaction moment norm of each joint (about its origin) along the motion",
        _per("peak_moment", joint_names),
        _peaks("peak_moment", lambda s: s.moments, joint_names),
    ),
    Metric(
        "singularity_distance",
        "-",
        "smallest inverse condition number of the passive block along the motion (0: singular)",
        lambda m: ["singularity_distance"],
        lambda m, s: {"singularity_distance": float(np.min(s.inv_cond))},
    ),
    Metric(
        "closure_residual",
        "m",
        "largest closure residual along the motion",
        lambda m: ["closure_residual"],
        lambda m, s: {"closure_residual": float(np.max(s.residual))},
    ),
)

#: Metrics of the elastic model (`mechkit.elastic`), asked for by name (in no default set).
ELASTIC = (
    Metric("mass", "kg", "total mass of the bodies", lambda m: ["mass"], lambda m, s: {"mass": _mass(m)}, motion=False),
    Metric(
        "first_frequency",
        "Hz",
        "first natural frequency at home, actuators locked (mechkit.elastic)",
        lambda m: ["first_frequency"],
        lambda m, s: {"first_frequency": _first_frequency(m)},
        motion=False,
    ),
    Metric(
        "frequency_per_mass",
        "Hz/kg",
        "first natural frequency per kilogram of the mechanism",
        lambda m: ["frequency_per_mass"],
        lambda m, s: {"frequency_per_mass": _first_frequency(m) / _mass(m)},
        motion=False,
    ),
    Metric(
        "stiffness",
        "N/m, N m/rad",
        "1/C_ii of the heaviest moving body at its centre of mass, home pose, "
        "actuators locked (every other direction free)",
        lambda m: list(STIFFNESS_COLUMNS),
        _stiffness,
        motion=False,
    ),
)
