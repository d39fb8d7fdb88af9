"""The elastic data of a mechanism: a beam section per link, an elasticity per joint.

Rigid by default: a link without a section is rigid, a joint without an elasticity is ideal (rigid in
its constrained directions) and, when actuated, locked. SI units throughout.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from mechkit.base.exceptions import InvalidParameters


def _vector(name: str, value: object, size: int) -> np.ndarray:
    """A finite float array of `size` entries, read-only."""
    try:
        out = np.array(value, dtype=float).reshape(size)
    except (TypeError, ValueError):
        raise InvalidParameters(name, value, f"expected {size} numbers") from None
    if not np.all(np.isfinite(out)):
        raise InvalidParameters(name, value, "must be finite")
    out.flags.writeable = False
    return out


#: Largest value of a section's property (SI, ours): far beyond any material or section (steel's E is 2e11 Pa),
#: far inside what double precision can multiply in a beam's stiffness.
LARGEST = 1e30


@dataclass(frozen=True, eq=False)
class Section:
    """A uniform beam section and its material (axial, Euler-Bernoulli bending, St Venant torsion).

    Attributes:
        E: Young's modulus (Pa).
        G: shear modulus (Pa).
        A: area (m^2).
        I1: second moment of area (m^4) about `axis1`.
        I2: second moment of area (m^4) about the direction normal to both the beam and `axis1`.
        J: torsion constant (m^4).
        axis1: (3,) the direction, in the link's frame, I1 is about (for a planar linkage its
            revolute axis); its part along each beam is dropped.
        density: material density (kg/m^3), for the mass of a design (`Section.mass`), not for the
            dynamics, which take the link's own inertia from its description.

    Raises:
        InvalidParameters: a non-positive or non-finite value, a zero axis1.
    """

    E: float
    G: float
    A: float
    I1: float
    I2: float
    J: float
    axis1: np.ndarray = field(default_factory=lambda: np.array([0.0, 0.0, 1.0]))
    density: float = 0.0

    def __post_init__(self) -> None:
        for name in ("E", "G", "A", "I1", "I2", "J"):
            value = getattr(self, name)
            if not isinstance(value, (int, float)) or not math.isfinite(value) or not 0 < value <= LARGEST:
                raise InvalidParameters(name, value, f"must be a number > 0 and <= {LARGEST:g} (SI units)")
        if not math.isfinite(self.density) or self.density < 0:
            raise InvalidParameters("density", self.density, "must be a finite number >= 0 (kg/m^3)")
        axis = _vector("axis1", self.axis1, 3)
        if not np.any(axis):
            raise InvalidParameters("axis1", self.axis1, "must be a non-zero direction")
        axis = axis / np.max(np.abs(axis))  # scaled first: the norm of 1e300 components would overflow
        object.__setattr__(self, "axis1", _vector("axis1", axis / np.linalg.norm(axis), 3))

    @classmethod
    def tube(
        cls, outer: float, inner: float, E: float, G: float, axis1: object = (0.0, 0.0, 1.0), density: float = 0.0
    ) -> Section:
        """A round tube: I1 = I2 = pi (D^4 - d^4) / 64, J = 2 I1.

        Args:
            outer: outer diameter D (m).
            inner: inner diameter d (m; 0: a solid rod).
            E: Young's modulus (Pa).
            G: shear modulus (Pa).
            axis1: (3,) the direction I1 is about, in the link's frame.
            density: material density (kg/m^3).

        Returns:
            The `Section`.

        Raises:
            InvalidParameters: not 0 <= inner < outer.
        """
        if not (math.isfinite(outer) and math.isfinite(inner) and 0.0 <= inner < outer):
            raise InvalidParameters("outer/inner", (outer, inner), "need 0 <= inner < outer (m)")
        inertia = math.pi * (outer**4 - inner**4) / 64.0
        return cls(
            E, G, math.pi * (outer**2 - inner**2) / 4.0, inertia, inertia, 2.0 * inertia, np.asarray(axis1), density
        )

    def mass(self, length: float) -> float:
        """The mass of a straight beam of this section.

        Args:
            length: the beam's length (m).

        Returns:
            Its mass (kg): density A length.
        """
        return self.density * self.A * length

    def scaled(self, factor: float) -> Section:
        """The same section with both moduli times a factor (every stiffness times it).

        Args:
            factor: the factor (> 0).

        Returns:
            The scaled `Section`.
        """
        return replace(self, E=self.E * factor, G=self.G * factor)


@dataclass(frozen=True, eq=False)
class JointElasticity:
    """What is elastic about one joint (tree joint or cut).

    Attributes:
        centre: position (m) of the joint's centre along its axis from the joint's origin (a revolute
            whose frame sits elsewhere on its axis, e.g. at a spherical mechanism's centre).
        stiffness: (6,) diagonal stiffness [kx, ky, kz, krx, kry, krz] (N/m, N m/rad) in the joint's
            frame (a cut: frame_a's), or None (ideal). Only the joint's constrained directions use it;
            `inf` keeps a direction rigid.
        drive: drive stiffness (N m/rad or N/m) of an actuated joint, None: locked.

    Raises:
        InvalidParameters: a negative, zero or nan stiffness.
    """

    centre: float = 0.0
    stiffness: np.ndarray | None = None
    drive: float | None = None

    def __post_init__(self) -> None:
        if not abs(self.centre) <= LARGEST:
            raise InvalidParameters("centre", self.centre, f"must be finite, at most {LARGEST:g} m")
        if self.stiffness is not None:
            k = np.array(self.stiffness, dtype=float).reshape(-1)
            if k.shape != (6,) or np.any(np.isnan(k)) or np.any(k <= 0):
                raise InvalidParameters("stiffness", self.stiffness, "expected 6 values > 0 (N/m, N m/rad; inf: rigid)")
            k.flags.writeable = False
            object.__setattr__(self, "stiffness", k)
        if self.drive is not None and not (self.drive > 0 and not math.isnan(self.drive)):
            raise InvalidParameters("drive", self.drive, "must be > 0 (N m/rad or N/m; inf: locked)")


@dataclass(frozen=True)
class ElasticData:
    """The elastic data of a mechanism: link name -> `Section`, joint name -> `JointElasticity`.

    Link names are the description's (URDF links); joint names are tree joints or cuts.
    """

    sections: dict[str, Section] = field(default_factory=dict)
    joints: dict[str, JointElasticity] = field(default_factory=dict)

    def __bool__(self) -> bool:
        return bool(self.sections or self.joints)

    def with_section(self, link: str, section: Section | None) -> ElasticData:
        """A copy with one link's section set.

        Args:
            link: the URDF link.
            section: its section (None: the link rigid).

        Returns:
            The new `ElasticData`.
        """
        sections = {k: v for k, v in self.sections.items() if k != link}
        if section is not None:
            sections[link] = section
        return ElasticData(sections, dict(self.joints))

    def with_joint(self, joint: str, elasticity: JointElasticity | None) -> ElasticData:
        """A copy with one joint's elasticity set.

        Args:
            joint: the joint (a tree joint or a cut).
            elasticity: its elasticity (None: ideal and, when actuated, locked).

        Returns:
            The new `ElasticData`.
        """
        joints = {k: v for k, v in self.joints.items() if k != joint}
        if elasticity is not None:
            joints[joint] = elasticity
        return ElasticData(dict(self.sections), joints)

    def scaled(self, factor: float) -> ElasticData:
        """A copy with every section's moduli, joint stiffness and drive stiffness times a factor.

        Args:
            factor: the factor (> 0).

        Returns:
            The scaled `ElasticData`.
        """
        joints = {
            name: replace(
                j,
                stiffness=None if j.stiffness is None else j.stiffness * factor,
                drive=None if j.drive is None else j.drive * factor,
            )
            for name, j in self.joints.items()
        }
        return ElasticData({name: s.scaled(factor) for name, s in self.sections.items()}, joints)
