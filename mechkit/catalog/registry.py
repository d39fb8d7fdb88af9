"""The registry: an explicit table of the mechanisms that ship with mechkit, loaded lazily.

Each entry names the package that declares the mechanism (`SPEC`, a `MechanismSpec`) and the line
`mechkit list` prints, so listing imports no mechanism and `get_spec(name)` imports that one alone.
A test checks the table against the packages, the templates and the generated URDFs.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from functools import cache

from mechkit.base.exceptions import InvalidParameters
from mechkit.catalog.contract import MechanismSpec


@dataclass(frozen=True)
class Entry:
    """One registered mechanism: its name, the package declaring its `SPEC`, its one-line summary."""

    name: str
    package: str
    summary: str


ENTRIES: tuple[Entry, ...] = (
    Entry(
        "deployable_9rr12uru",
        "mechkit.mechanisms.deployable_9rr12uru",
        "9RR-12URU deployable composite element of a truss antenna (3 tetrahedral units + 3 URU chains)",
    ),
    Entry("five_bar", "mechkit.mechanisms.five_bar", "planar five-bar, 2-DOF calibration mechanism of the core"),
    Entry(
        "four_bar", "mechkit.mechanisms.four_bar", "planar four-bar (crank-rocker), calibration mechanism of the core"
    ),
    Entry(
        "parallel_2t1r",
        "mechkit.mechanisms.parallel_2t1r",
        "spatial 2T1R parallel mechanism, five-bar limb + 2 RRR limbs, all axes along y (ref. 001)",
    ),
    Entry(
        "rocket_gimbal",
        "mechkit.mechanisms.rocket_gimbal",
        "launcher engine gimbal: frame-bracket-engine hinges at 45 deg, two U-P-S servo actuators",
    ),
    Entry(
        "spherical_2dof",
        "mechkit.mechanisms.spherical_2dof",
        "2-DOF spherical parallel platform (2 RRR limbs + central Hooke strut), vibration isolation",
    ),
    Entry(
        "ten_bar",
        "mechkit.mechanisms.ten_bar",
        "Radarsat-2 solar-array ten-bar (patent CN105975733): 9 links, 12 pairs, 2 motors + 1 spring DOF",
    ),
    Entry(
        "tetra_3rr3uru",
        "mechkit.mechanisms.tetra_3rr3uru",
        "3RR-3URU tetrahedral deployable unit H-ABE of a truss antenna, node A fixed",
    ),
)


def names() -> tuple[str, ...]:
    """Registered mechanism names, sorted (imports no mechanism)."""
    return tuple(e.name for e in ENTRIES)


def entry(name: str) -> Entry:
    """The registry entry of a name.

    Args:
        name: a mechanism's name.

    Returns:
        Its entry (name, package, summary).

    Raises:
        InvalidParameters: no such mechanism.
    """
    for e in ENTRIES:
        if e.name == name:
            return e
    raise InvalidParameters("name", name, f"no such mechanism; registered: {', '.join(names())}")


@cache
def get_spec(name: str) -> MechanismSpec:
    """The spec of a registered mechanism: imports its package (and no other mechanism's).

    Args:
        name: a registered mechanism's name.

    Returns:
        Its `SPEC`.

    Raises:
        InvalidParameters: no such mechanism, or its package declares no `SPEC` of that name.
    """
    e = entry(name)
    try:
        spec = importlib.import_module(e.package).SPEC
    except AttributeError:
        spec = None
    if not isinstance(spec, MechanismSpec) or spec.name != name:
        raise InvalidParameters("name", name, f"{e.package} does not declare SPEC = MechanismSpec(name={name!r}, ...)")
    return spec


def specs() -> dict[str, MechanismSpec]:
    """Every registered mechanism's spec, by name (imports them all: for tests, tools and benches)."""
    return {name: get_spec(name) for name in names()}
