"""Motion of a planar linkage at one instant (numpy only): bars, link motions, pins, the whole state.

Plane of motion: world x-z, z up. Revolute axes point along -y, so a positive angle turns +x
towards +z and a planar angle phi is the direction (cos phi, 0, sin phi). Planar vectors here are
(x, z) pairs with the ordinary counter-clockwise orientation: an angular rate w (rad/s) is the
world vector w * (0, -1, 0) and a counter-clockwise planar moment M (N m) is M * (0, -1, 0).

Links are rectangular bars along their local x, from their joint origin to their length L (width
along local z, thickness along y). The closed forms that fill these states are in
`mechkit.validation.planar_closed_form`, their Newton-Euler dynamics in
`mechkit.validation.planar_newton_euler`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechkit.base.exceptions import InvalidParameters

__all__ = ["AXIS", "Bar", "LinkState", "LinkageState", "PlanarJoint", "perp", "to_world", "unit"]

AXIS = np.array([0.0, -1.0, 0.0])
"""World direction of every revolute axis; rates and planar moments are components along it."""


def to_world(v: np.ndarray) -> np.ndarray:
    """A planar (x, z) vector as a world vector (x, 0, z).

    Args:
        v: the planar vector (2,).

    Returns:
        The world vector (3,).
    """
    return np.array([v[0], 0.0, v[1]])


def unit(angle: float) -> np.ndarray:
    """The planar unit vector at an angle from +x towards +z.

    Args:
        angle: the angle, rad.

    Returns:
        (2,) unit vector.
    """
    return np.array([np.cos(angle), np.sin(angle)])


def perp(v: np.ndarray) -> np.ndarray:
    """A planar vector turned +90 degrees (counter-clockwise, +x towards +z).

    Args:
        v: the vector (2,).

    Returns:
        The turned vector (2,).
    """
    return np.array([-v[1], v[0]])


@dataclass(frozen=True)
class Bar:
    """Rectangular aluminium bar along its local x (SI units).

    Attributes:
        length: m, joint origin to tip; the COM is at length / 2.
        width: m, in the plane (local z).
        thickness: m, along y.
        density: kg/m^3.
    """

    length: float
    width: float = 0.02
    thickness: float = 0.01
    density: float = 2700.0

    @property
    def mass(self) -> float:
        """kg."""
        return self.density * self.length * self.width * self.thickness

    @property
    def inertia_planar(self) -> float:
        """kg m^2, about the axis through the COM normal to the plane (y)."""
        return self.mass * (self.length**2 + self.width**2) / 12.0

    def inertia_world(self, angle: float) -> np.ndarray:
        """The box inertia about the COM in world axes.

        Args:
            angle: the bar's planar angle, rad.

        Returns:
            (3, 3) inertia, kg m^2.
        """
        m, length, w, t = self.mass, self.length, self.width, self.thickness
        local = np.diag([m * (t**2 + w**2), m * (length**2 + w**2), m * (length**2 + t**2)]) / 12.0
        c, s = np.cos(angle), np.sin(angle)
        rot = np.array([[c, 0.0, -s], [0.0, 1.0, 0.0], [s, 0.0, c]])  # columns: local x, y, z
        return rot @ local @ rot.T


@dataclass(frozen=True)
class LinkState:
    """Motion of one bar at one instant (planar (x, z) vectors, m, rad, s).

    Attributes:
        name: link name.
        bar: its geometry and inertia.
        origin: position of its joint origin.
        angle: planar angle of the bar's axis.
        omega: angular rate (about -y).
        alpha: angular acceleration (about -y).
        origin_velocity: velocity of the origin.
        origin_acceleration: acceleration of the origin.
    """

    name: str
    bar: Bar
    origin: np.ndarray
    angle: float
    omega: float
    alpha: float
    origin_velocity: np.ndarray
    origin_acceleration: np.ndarray

    def point(self, s: float) -> np.ndarray:
        """Position of a point of the bar.

        Args:
            s: its distance along the bar from the origin, m.

        Returns:
            (2,) planar position, m.
        """
        return self.origin + s * unit(self.angle)

    def point_velocity(self, s: float) -> np.ndarray:
        """Velocity of a point of the bar.

        Args:
            s: its distance along the bar from the origin, m.

        Returns:
            (2,) planar velocity, m/s.
        """
        return self.origin_velocity + s * self.omega * perp(unit(self.angle))

    def point_acceleration(self, s: float) -> np.ndarray:
        """Acceleration of a point of the bar.

        Args:
            s: its distance along the bar from the origin, m.

        Returns:
            (2,) planar acceleration, m/s^2.
        """
        e = unit(self.angle)
        return self.origin_acceleration + s * (self.alpha * perp(e) - self.omega**2 * e)

    @property
    def tip(self) -> np.ndarray:
        """Position (m) of the bar's far end."""
        return self.point(self.bar.length)

    @property
    def com(self) -> np.ndarray:
        """Position (m) of the bar's centre of mass (its midpoint)."""
        return self.point(0.5 * self.bar.length)

    @property
    def com_velocity(self) -> np.ndarray:
        """Velocity (m/s) of the centre of mass."""
        return self.point_velocity(0.5 * self.bar.length)

    @property
    def com_acceleration(self) -> np.ndarray:
        """Acceleration (m/s^2) of the centre of mass."""
        return self.point_acceleration(0.5 * self.bar.length)


@dataclass(frozen=True)
class PlanarJoint:
    """A pin of a planar linkage.

    Attributes:
        name: joint name (URDF joint or loop-cut name).
        parent: link on the parent side (frame_a's for a cut), None for the ground.
        child: link on the child side.
        point: planar position (x, z) of the pin, m.
        actuated: whether a motor torque acts about the pin (parent on child, about -y).
    """

    name: str
    parent: str | None
    child: str
    point: np.ndarray
    actuated: bool = False


@dataclass(frozen=True)
class LinkageState:
    """Complete motion of a planar linkage at one instant.

    Attributes:
        links: link name -> its motion.
        joints: every pin, loop cuts included.
        coordinates: joint names of the URDF coordinates q, in order.
        q: joint coordinates (rad): absolute angle for a grounded joint, relative angle (child
            minus parent, wrapped to (-pi, pi]) otherwise.
        qd: their rates (rad/s).
        qdd: their accelerations (rad/s^2).
    """

    links: dict[str, LinkState]
    joints: tuple[PlanarJoint, ...]
    coordinates: tuple[str, ...]
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray

    def joint(self, name: str) -> PlanarJoint:
        """The pin called ``name``.

        Args:
            name: the pin's name.

        Returns:
            The pin.

        Raises:
            InvalidParameters: no pin of that name.
        """
        for j in self.joints:
            if j.name == name:
                return j
        raise InvalidParameters("joint", name, f"not a joint of this linkage {[j.name for j in self.joints]}")

    def joint_position(self, name: str) -> np.ndarray:
        """World (3,) position of the pin called ``name``, m.

        Args:
            name: the pin's name.

        Returns:
            World position (3,), m.
        """
        return to_world(self.joint(name).point)
