"""Sequential single-open-chain (SOC) virtual-work inverse dynamics, numpy only.

A mechanism is split into an ordered list of SKCs (single kinematic chains). Each SKC is given, at
one instant, by the inertial loads of its bodies, the virtual-displacement Jacobians of its bodies
and joint points over its own virtual coordinates, its actuators, and the joints linking it to
other SKCs: "released" joints (reactions unknown, solved here) and "known" joints (reactions
solved by an earlier SKC). Per SKC the virtual-work equations N^T Q = 0 are linear in the unknown
efforts and reactions. The only dynamics are per-body inertial loads: no mass matrix, no RNEA.

Conventions: every vector is in the world frame. A joint reaction is the wrench (6,)
``[fx, fy, fz, mx, my, mz]`` (N, N m) that the joint's parent side exerts on its child side, at the
joint point. The Jacobians are supplied by the caller (analytic or from the mechanism's geometry).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from scipy.linalg import null_space

from mechkit.base.exceptions import InvalidParameters, SingularConfiguration
from mechkit.base.spatial import cross

__all__ = [
    "RANK_TOL",
    "BodyLoad",
    "SKCInstant",
    "SOCResult",
    "WrenchSite",
    "classic_virtual_work",
    "solve_soc",
]

RANK_TOL = 1e-10
"""Relative singular-value tolerance below which an SKC system counts as rank-deficient."""

FREE_TOL = 1e-8
"""Relative variation along an SKC's null space above which a value counts as not fixed (``free``)."""

STANDARD_GRAVITY = (0.0, 0.0, -9.81)
"""Default gravity (m/s^2, world frame): 9.81 along -z."""

_ALL_COMPONENTS = (0, 1, 2, 3, 4, 5)


@dataclass(frozen=True)
class BodyLoad:
    """One rigid body of an SKC at one instant (world frame).

    Attributes:
        name: body name (for messages).
        mass: kg.
        inertia_com: (3, 3) kg m^2, about the centre of mass, world axes at this instant.
        com_acceleration: (3,) m/s^2.
        omega: (3,) angular velocity, rad/s.
        alpha: (3,) angular acceleration, rad/s^2.
        jv: (3, n) virtual displacement of the COM per unit virtual coordinate, m.
        jw: (3, n) virtual rotation of the body per unit virtual coordinate, rad.
    """

    name: str
    mass: float
    inertia_com: np.ndarray
    com_acceleration: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray
    jv: np.ndarray
    jw: np.ndarray


@dataclass(frozen=True)
class WrenchSite:
    """A joint wrench acting on an SKC.

    Attributes:
        joint: joint name (the key of the reaction).
        jacobian: (6, n): rows 0-2 virtual displacement of the joint point on THIS SKC's side,
            rows 3-5 virtual rotation of the body on this side (world).
        sign: +1 if this SKC holds the joint's child side (the reaction acts on it as +w),
            -1 if it holds the parent side.
        components: for a released joint, which of the six world components (fx fy fz mx my mz)
            are unknowns; the others are zero by convention (e.g. (0, 2) for a pin of an x-z
            planar linkage). Ignored for a known joint (its full stored wrench is applied).
        basis: for a released joint whose unknowns are not world components, (6, k) world wrench
            directions of its k unknowns (reaction = basis @ x); when given, ``components`` is
            ignored. E.g. the constraint moment of a Hooke joint along the turning a1 x a2.
    """

    joint: str
    jacobian: np.ndarray
    sign: float
    components: tuple[int, ...] = _ALL_COMPONENTS
    basis: np.ndarray | None = None


@dataclass(frozen=True)
class SKCInstant:
    """One SKC at one instant.

    Attributes:
        name: SKC name (for results and messages).
        n: number of virtual coordinates of this SKC.
        bodies: its rigid bodies.
        actuators: (name, (n,) generalized-force direction of a unit effort) per actuator solved here.
        released: joints to SKCs not yet solved: their reactions are unknowns of this SKC.
        known: joints to SKCs already solved: reactions taken from earlier SKCs.
        external: (wrench (6,) world at the point, jacobian (6, n)) per applied load.
        loop_jacobian: (m, n) internal closure Jacobian; the virtual displacements are its null
            space (all of R^n when None).
    """

    name: str
    n: int
    bodies: Sequence[BodyLoad]
    actuators: Sequence[tuple[str, np.ndarray]] = ()
    released: Sequence[WrenchSite] = ()
    known: Sequence[WrenchSite] = ()
    external: Sequence[tuple[np.ndarray, np.ndarray]] = ()
    loop_jacobian: np.ndarray | None = None


@dataclass(frozen=True)
class SOCResult:
    """Result of :func:`solve_soc`.

    Attributes:
        efforts: actuator name -> effort (N m for a revolute, N for a prismatic actuator).
        reactions: joint -> (6,) wrench parent-on-child at the joint point, world.
        consistency: SKC -> relative residual of its virtual-work equations
            (|N^T Q| / |N^T Q_known|; nonzero only for an over-determined SKC).
        condition: SKC -> condition number of its linear solve.
        free: only with ``indeterminate=True``: joint -> (6,) bool, the world components of its
            reaction that the SKC's equations do not fix.
        free_efforts: only with ``indeterminate=True``: actuator -> whether its SKC leaves it free.
    """

    efforts: dict[str, float] = field(default_factory=dict)
    reactions: dict[str, np.ndarray] = field(default_factory=dict)
    consistency: dict[str, float] = field(default_factory=dict)
    condition: dict[str, float] = field(default_factory=dict)
    free: dict[str, np.ndarray] = field(default_factory=dict)
    free_efforts: dict[str, bool] = field(default_factory=dict)


def _array(value: object, shape: tuple[int, ...], name: str) -> np.ndarray:
    """Return ``value`` as a float array of ``shape``, or raise InvalidParameters naming it."""
    arr = np.asarray(value, dtype=float)
    if arr.shape != shape:
        raise InvalidParameters(name, arr.shape, f"expected shape {shape}")
    if not np.all(np.isfinite(arr)):
        raise InvalidParameters(name, value, "contains NaN or inf")
    return arr


def _known_forces(skc: SKCInstant, gravity: np.ndarray, reactions: dict[str, np.ndarray]) -> np.ndarray:
    """Generalized forces (n,) of everything known on ``skc``: gravity, inertia, known joints, loads."""
    n = skc.n
    forces = np.zeros(n)
    for b in skc.bodies:
        where = f"SKC {skc.name!r} body {b.name!r}"
        if not (np.isfinite(b.mass) and b.mass >= 0.0):
            raise InvalidParameters(f"{where} mass", b.mass, "must be finite and non-negative")
        inertia = _array(b.inertia_com, (3, 3), f"{where} inertia_com")
        omega = _array(b.omega, (3,), f"{where} omega")
        force = b.mass * (gravity - _array(b.com_acceleration, (3,), f"{where} com_acceleration"))
        moment = -inertia @ _array(b.alpha, (3,), f"{where} alpha") - cross(omega, inertia @ omega)
        forces += _array(b.jv, (3, n), f"{where} jv").T @ force
        forces += _array(b.jw, (3, n), f"{where} jw").T @ moment
    for site in skc.known:
        if site.joint not in reactions:
            why = "no earlier SKC released this joint"
            raise InvalidParameters(f"SKC {skc.name!r} known", site.joint, why)
        jac = _array(site.jacobian, (6, n), f"SKC {skc.name!r} known {site.joint!r} jacobian")
        forces += jac.T @ (site.sign * reactions[site.joint])
    for i, (wrench, jacobian) in enumerate(skc.external):
        where = f"SKC {skc.name!r} external[{i}]"
        forces += _array(jacobian, (6, n), f"{where} jacobian").T @ _array(wrench, (6,), f"{where} wrench")
    return forces


def _directions(skc: SKCInstant, site: WrenchSite) -> np.ndarray:
    """(6, k) world wrench directions of a released site's k unknowns."""
    where = f"SKC {skc.name!r} released {site.joint!r}"
    if site.basis is not None:
        basis = np.asarray(site.basis, dtype=float)
        k = basis.shape[1] if basis.ndim == 2 else 0
        if k == 0:
            raise InvalidParameters(f"{where} basis", basis.shape, "expected shape (6, k), k >= 1")
        return _array(basis, (6, k), f"{where} basis")
    if not site.components or not set(site.components) <= set(_ALL_COMPONENTS):
        raise InvalidParameters(f"{where} components", site.components, "must be a non-empty subset of 0..5")
    return np.eye(6)[:, list(site.components)]


def _unknown_columns(skc: SKCInstant, directions: Sequence[np.ndarray]) -> np.ndarray:
    """Generalized-force columns (n, k) of the unknowns: actuator efforts, then released reactions."""
    n = skc.n
    cols = [_array(d, (n,), f"SKC {skc.name!r} actuator {a!r}") for a, d in skc.actuators]
    for site, basis in zip(skc.released, directions, strict=True):
        jac = _array(site.jacobian, (6, n), f"SKC {skc.name!r} released {site.joint!r} jacobian")
        cols.extend((site.sign * jac.T @ basis).T)
    return np.column_stack(cols) if cols else np.zeros((n, 0))


def solve_soc(
    skcs: Sequence[SKCInstant], gravity: np.ndarray | Sequence[float] = STANDARD_GRAVITY, indeterminate: bool = False
) -> SOCResult:
    """Inverse dynamics by sequential SOC virtual work.

    Per SKC, in order: Q = sum_bodies jv^T (m g - m a_c) + jw^T (-I alpha - omega x I omega)
    + sum_known J^T (sign w) + sum_external J^T w + sum_actuators d u
    + sum_released J^T B (sign R) (B: the site's unknown wrench directions); the virtual work
    N^T Q = 0 (N spans the null space of the SKC's loop Jacobian) is solved for (u, R) by least
    squares.

    Args:
        skcs: the SKCs in solving order; a joint released by one SKC may be known in later ones.
        gravity: (3,) m/s^2, world.
        indeterminate: where an SKC's system does not determine its unknowns (redundant
            constraints or actuation), take its minimum-norm solution and record in ``free`` which
            efforts and reaction components vary along its null space, instead of raising.

    Returns:
        Efforts, reactions (parent on child, world, at the joint point; zero outside the declared
        components / basis), and per SKC the consistency residual and condition number.

    Raises:
        SingularConfiguration: (without ``indeterminate``) an SKC's system does not determine its
            unknowns (relative smallest singular value below RANK_TOL, or fewer equations than unknowns).
        InvalidParameters: malformed SKC data (shapes, NaN, a known joint never released, a joint
            released twice, an actuator solved twice).
    """
    gravity = _array(gravity, (3,), "gravity")
    result = SOCResult()
    for skc in skcs:
        for name, _ in skc.actuators:
            if name in result.efforts:
                why = "effort already solved by an earlier SKC"
                raise InvalidParameters(f"SKC {skc.name!r} actuators", name, why)
        for site in skc.released:
            if site.joint in result.reactions:
                why = "reaction already solved by an earlier SKC"
                raise InvalidParameters(f"SKC {skc.name!r} released", site.joint, why)

        null = _virtual_basis(skc)
        rhs = -null.T @ _known_forces(skc, gravity, result.reactions)
        directions = [_directions(skc, site) for site in skc.released]
        matrix = null.T @ _unknown_columns(skc, directions)
        if indeterminate:
            x, cond, null = _solve_min_norm(matrix, rhs)
            _record_free(result, skc, directions, null)
        else:
            x, cond = _solve_determinate(matrix, rhs, skc.name)
        result.condition[skc.name] = cond
        residual = np.linalg.norm(matrix @ x - rhs)
        result.consistency[skc.name] = float(residual / max(np.linalg.norm(rhs), np.finfo(float).tiny))

        for (name, _), u in zip(skc.actuators, x[: len(skc.actuators)], strict=True):
            result.efforts[name] = float(u)
        i = len(skc.actuators)
        for site, site_directions in zip(skc.released, directions, strict=True):
            k = site_directions.shape[1]
            result.reactions[site.joint] = site_directions @ x[i : i + k]
            i += k
    return result


def _virtual_basis(skc: SKCInstant) -> np.ndarray:
    """Basis (n, d) of the SKC's virtual displacements: null space of its loop Jacobian."""
    if skc.loop_jacobian is None:
        return np.eye(skc.n)
    loop = np.asarray(skc.loop_jacobian, dtype=float)
    if loop.ndim != 2 or loop.shape[1] != skc.n or not np.all(np.isfinite(loop)):
        why = f"expected a finite (m, {skc.n}) matrix"
        raise InvalidParameters(f"SKC {skc.name!r} loop_jacobian", loop.shape, why)
    return null_space(loop, rcond=RANK_TOL)


def _solve_determinate(matrix: np.ndarray, rhs: np.ndarray, skc: str) -> tuple[np.ndarray, float]:
    """Least-squares solution of ``matrix x = rhs`` and its condition number; raise if rank-deficient."""
    k = matrix.shape[1]
    if k == 0:
        return np.zeros(0), 1.0
    sv = np.linalg.svd(matrix, compute_uv=False)
    if len(sv) < k or sv[-1] <= RANK_TOL * sv[0]:
        cond = np.inf if len(sv) < k or sv[-1] == 0.0 else float(sv[0] / sv[-1])
        what = f"SKC {skc!r} virtual-work system ({matrix.shape[0]} equations, {k} unknowns)"
        raise SingularConfiguration(cond, what)
    return np.linalg.lstsq(matrix, rhs, rcond=None)[0], float(sv[0] / sv[-1])


def _solve_min_norm(matrix: np.ndarray, rhs: np.ndarray) -> tuple[np.ndarray, float, np.ndarray]:
    """Minimum-norm least-squares solution, condition number of the kept part, null space (k, d)."""
    k = matrix.shape[1]
    if k == 0:
        return np.zeros(0), 1.0, np.zeros((0, 0))
    u, sv, vt = np.linalg.svd(matrix, full_matrices=True)
    rank = int(np.sum(sv > RANK_TOL * sv[0])) if sv.size and sv[0] > 0.0 else 0
    x = vt[:rank].T @ ((u[:, :rank].T @ rhs) / sv[:rank])
    cond = float(sv[0] / sv[rank - 1]) if rank else np.inf
    return x, cond, vt[rank:].T


def _record_free(result: SOCResult, skc: SKCInstant, directions: Sequence[np.ndarray], null: np.ndarray) -> None:
    """Store in ``result`` which efforts and reaction components of ``skc`` vary along ``null``."""
    na = len(skc.actuators)
    efforts = np.abs(null[:na]).max(axis=1, initial=0.0)
    reactions = []
    i = na
    for basis in directions:
        k = basis.shape[1]
        reactions.append(np.abs(basis @ null[i : i + k]).max(axis=1, initial=0.0))
        i += k
    scale = max([float(efforts.max(initial=0.0))] + [float(v.max(initial=0.0)) for v in reactions])
    threshold = FREE_TOL * scale if scale > 0.0 else np.inf
    for (name, _), v in zip(skc.actuators, efforts, strict=True):
        result.free_efforts[name] = bool(v > threshold)
    for site, v in zip(skc.released, reactions, strict=True):
        result.free[site.joint] = v > threshold


def classic_virtual_work(skc: SKCInstant, gravity: np.ndarray | Sequence[float] = STANDARD_GRAVITY) -> dict[str, float]:
    """Classic whole-mechanism virtual work: one SKC holding every body and every actuator.

    Args:
        skc: the whole mechanism (its loop closures in ``loop_jacobian``), no released or known joints.
        gravity: (3,) m/s^2, world.

    Returns:
        Actuator name -> effort (N m or N).

    Raises:
        InvalidParameters: the SKC has released or known joints.
    """
    if skc.released or skc.known:
        raise InvalidParameters("skc", skc.name, "classic virtual work takes no released or known joints")
    return solve_soc([skc], gravity).efforts
