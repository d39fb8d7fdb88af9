"""MJCF spatial tendons between two sites, and the actuators on them, as point-to-point elements
(`mechkit.forces.PointToPoint`, whose convention is MuJoCo's: a positive force lengthens the tendon).

- a spatial tendon of two sites with `stiffness`, `damping` and `springlength` -> a `PointToPoint` named
  after the tendon: stiffness (N/m), damping (N s/m), free length the spring length (MuJoCo's
  length at qpos0 where the file gives none); none where `<flag spring="disable">` / `damper="disable"`
  leave nothing.
- an actuator on such a tendon with a fixed gain and no or an affine bias, no activation dynamics (MuJoCo's
  motor, position and velocity actuators): its force gear (gain ctrl + b0 + b1 gear L + b2 gear L_dot) is
  a `PointToPoint` named after the actuator: stiffness -gear^2 b1 (free length 0), damping -gear^2 b2,
  constant force gear (gain ctrl + b0), with ctrl the keyframe "home"'s (0 without one).

Refused by name: a spatial tendon through other than two sites (wrapping geoms, pulleys, more sites), a
spring's dead band (two spring lengths), polynomial stiffness or damping, plasticity, armature,
friction loss or length limits on a spatial tendon; an actuator on one with activation dynamics, another
gain or bias, a force range, or a bias that is a negative spring or damper.
"""

from __future__ import annotations

from types import ModuleType
from typing import TYPE_CHECKING

import numpy as np

from mechkit.base.exceptions import MalformedDescription
from mechkit.core import PointToPoint
from mechkit.sources.mjcf.tree import object_names

if TYPE_CHECKING:
    from mujoco import MjModel

WRAP_JOINT, WRAP_SITE = 1, 3  # mjtWrap
TRN_TENDON = 3  # mjtTrn
SPRING_OFF, DAMPER_OFF = 1 << 5, 1 << 6  # mjtDisableBit


def spatial(mm: MjModel, t: int) -> bool:
    """Whether a tendon is spatial (any wrap not a joint).

    Args:
        mm: the compiled MuJoCo model.
        t: the tendon's id.

    Returns:
        True for a spatial tendon, False for a fixed one.
    """
    adr, num = int(mm.tendon_adr[t]), int(mm.tendon_num[t])
    return any(int(mm.wrap_type[w]) != WRAP_JOINT for w in range(adr, adr + num))


def _sites(mm: MjModel, names: dict[str, list[str]], t: int) -> tuple[str, str]:
    """The two sites of a spatial tendon, or a refusal."""
    adr, num = int(mm.tendon_adr[t]), int(mm.tendon_num[t])
    kinds = [int(mm.wrap_type[w]) for w in range(adr, adr + num)]
    if kinds != [WRAP_SITE, WRAP_SITE]:
        raise MalformedDescription(
            f"MJCF tendon {names['tendon'][t]!r}",
            "a spatial tendon is read between two sites only (no wrapping geoms, pulleys or further sites)",
        )
    return names["site"][int(mm.wrap_objid[adr])], names["site"][int(mm.wrap_objid[adr + 1])]


def _tendon(mm: MjModel, names: dict[str, list[str]], t: int) -> PointToPoint | None:
    """The spring and damper of one spatial tendon, or None where it has neither."""
    where = f"MJCF tendon {names['tendon'][t]!r}"
    a, b = _sites(mm, names, t)
    for field in ("tendon_stiffnesspoly", "tendon_dampingpoly", "tendon_armature", "tendon_frictionloss"):
        if np.any(np.asarray(getattr(mm, field)[t]) != 0):
            raise MalformedDescription(where, f"{field.removeprefix('tendon_')} on a spatial tendon is not read")
    if int(mm.tendon_limited[t]) or int(mm.tendon_plasticadr[t]) >= 0:
        raise MalformedDescription(where, "length limits or plasticity on a spatial tendon are not read")
    stiffness = float(mm.tendon_stiffness[t]) * (not mm.opt.disableflags & SPRING_OFF)
    damping = float(mm.tendon_damping[t]) * (not mm.opt.disableflags & DAMPER_OFF)
    low, high = (float(x) for x in mm.tendon_lengthspring[t])
    if stiffness and low != high:
        raise MalformedDescription(where, f"a spring dead band ({low:g} .. {high:g} m) is not read")
    if not (stiffness or damping):
        return None
    return PointToPoint(names["tendon"][t], a, b, stiffness=stiffness, free_length=low, damping=damping)


def _actuator(mm: MjModel, names: dict[str, list[str]], u: int, ctrl: float) -> PointToPoint:
    """An actuator on a spatial tendon as its force law (see the module docstring)."""
    where = f"MJCF actuator {names['actuator'][u]!r}"
    t = int(mm.actuator_trnid[u][0])
    if int(mm.actuator_dyntype[u]) != 0 or int(mm.actuator_gaintype[u]) != 0 or int(mm.actuator_biastype[u]) > 1:
        raise MalformedDescription(where, "on a spatial tendon, only fixed-gain actuators without dynamics are read")
    if int(mm.actuator_forcelimited[u]):
        raise MalformedDescription(where, "a force range on a spatial tendon's actuator is not read")
    gear, gain = float(mm.actuator_gear[u][0]), float(mm.actuator_gainprm[u][0])
    b0, b1, b2 = (float(x) for x in mm.actuator_biasprm[u][:3]) if int(mm.actuator_biastype[u]) else (0.0,) * 3
    if b1 > 0 or b2 > 0:
        raise MalformedDescription(where, "a bias that pushes away from its set point (b1 or b2 > 0) is not read")
    a, b = _sites(mm, names, t)
    return PointToPoint(
        names["actuator"][u],
        a,
        b,
        stiffness=-(gear**2) * b1,
        damping=-(gear**2) * b2,
        force=gear * (gain * ctrl + b0),
    )


def read(mujoco: ModuleType, mm: MjModel) -> tuple[PointToPoint, ...]:
    """The point-to-point elements of a model's spatial tendons and their actuators.

    Args:
        mujoco: the mujoco module.
        mm: the compiled MuJoCo model.

    Returns:
        The tendons' springs and dampers, then the actuators on spatial tendons (module docstring).

    Raises:
        MalformedDescription: what is refused by name (module docstring).
    """
    names = object_names(mujoco, mm)
    out = [p for t in range(mm.ntendon) if spatial(mm, t) and (p := _tendon(mm, names, t)) is not None]
    key = mujoco.mj_name2id(mm, mujoco.mjtObj.mjOBJ_KEY, "home")
    ctrl = mm.key_ctrl[key] if key >= 0 else np.zeros(mm.nu)
    for u in range(mm.nu):
        if int(mm.actuator_trntype[u]) == TRN_TENDON and spatial(mm, int(mm.actuator_trnid[u][0])):
            out.append(_actuator(mm, names, u, float(ctrl[u])))
    return tuple(out)
