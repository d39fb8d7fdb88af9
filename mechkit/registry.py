"""The registry of mechanisms: one module per mechanism under `mechkit/mechanisms/`, each with a `SPEC`."""

from __future__ import annotations

import importlib
import pkgutil
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING, Any

from mechkit.exceptions import InvalidParameters
from mechkit.params import MechanismParams

if TYPE_CHECKING:
    from mechkit.mechanism import Mechanism

XACRO_DIR = Path(__file__).resolve().parent.parent / "xacro"
URDF_DIR = Path(__file__).resolve().parent.parent / "urdf"

Inputs = Mapping[str, float]


@dataclass(frozen=True)
class MechanismSpec:
    """What mechkit needs to know about one mechanism besides its xacro template.

    Attributes:
        name: registry name (also the URDF file stem).
        params: the frozen parameter dataclass.
        xacro: template file name in `xacro/`.
        actuated: URDF joint names carrying actuators, or a function of the parameters giving them.
        gruebler_dof: the Gruebler-Kutzbach mobility count (int) for comparison with the numerical one.
        home: inputs (joint name -> value, rad or m) of the default assembly, from the parameters.
        guess: an initial guess (joint name -> value) that picks the assembly branch; optional.
        summary: one line for `mechkit list`.
        self_checks: optional extra `report` checks: Mechanism -> {check name: worst error}.
    """

    name: str
    params: type[MechanismParams]
    xacro: str
    actuated: tuple[str, ...] | Callable[[Any], tuple[str, ...]]
    gruebler_dof: int
    home: Callable[[Any], Inputs]
    guess: Callable[[Any], Inputs] | None = None
    summary: str = ""
    self_checks: Callable[[Mechanism], dict[str, float]] | None = None

    def actuated_joints(self, params: MechanismParams) -> tuple[str, ...]:
        return tuple(self.actuated(params) if callable(self.actuated) else self.actuated)

    @property
    def xacro_path(self) -> Path:
        return XACRO_DIR / self.xacro

    def default_urdf(self) -> str:
        """The URDF generated at the default parameters (what `urdf/<name>.urdf` must hold)."""
        from mechkit.description import render_urdf

        return render_urdf(self.xacro_path, self.params().xacro_args())


@cache
def specs() -> dict[str, MechanismSpec]:
    """Every registered mechanism, by name (modules of `mechkit.mechanisms` that define `SPEC`)."""
    import mechkit.mechanisms as package

    found: dict[str, MechanismSpec] = {}
    for info in sorted(pkgutil.iter_modules(package.__path__), key=lambda i: i.name):
        module = importlib.import_module(f"{package.__name__}.{info.name}")
        spec = getattr(module, "SPEC", None)
        if isinstance(spec, MechanismSpec):
            found[spec.name] = spec
    return found


def get_spec(name: str) -> MechanismSpec:
    """The spec of a registered mechanism; an unknown name raises `InvalidParameters`."""
    known = specs()
    if name not in known:
        raise InvalidParameters("name", name, f"no such mechanism; registered: {', '.join(known)}")
    return known[name]
