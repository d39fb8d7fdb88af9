"""The IFToMM multibody benchmark problems (tests/fixtures/iftomm/README.md: definitions and sources) run by
mechkit, each against a reference computed without mechkit's simulator, and by MuJoCo on the exported model.

References (scipy's `solve_ivp`, Pinocchio's kinematics and dynamics alone):

- the N-four-bar: on its branch every crank turns together, so it is the exact one-coordinate ODE
  theta'' = -K cos(theta) of `four_bar_gain` (`four_bar_reference`);
- Bricard's mechanism: one coordinate (joint O's angle) with the other joints solved from the closure by
  Gauss-Newton, their rates and curvature by 5-point differences, and the reduced Lagrange equation
  T^T (M T theta'' + rnea(q, T w, D w^2)) = 0 (`BricardChart`);
- the flyball governor: a tree, integrated by Pinocchio's ABA with the two spring-dampers' wrenches
  written here (`flyball_reference`, Radau).

The library's criterion: "high precision" is an error <= `HIGH_PRECISION` (m) of the problem's point.
MuJoCo runs `mechkit.export.to_mjcf` (stiff equalities, its own timestep, RK4); a thin rod's zero moment
about its own axis and a massless link's mass are raised to `MJ_AXIAL` there (MuJoCo refuses < 1e-15; ours).
"""

from __future__ import annotations

import copy
import time
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from typing import Any

import numpy as np
import pinocchio as pin
from scipy.integrate import solve_ivp

from mechkit.base.exceptions import InvalidArgument
from mechkit.export.mjcf import to_mjcf

#: The library's "high precision" bound on the error (m).
HIGH_PRECISION = 1e-3
#: Gravity of every problem (m/s^2).
G = 9.81
#: Moment (kg m^2) of a thin rod about its axis and mass (kg) of a massless link in MuJoCo's model (ours; > 1e-15).
MJ_AXIAL = 1e-9
#: Step (rad) of the 5-point differences of Bricard's chart (ours: truncation ~h^4, rounding ~1e-15 / h^2).
CHART_STEP = 1e-3
ROD = (
    '<inertial><origin xyz="0.5 0 0"/><mass value="1.0"/><inertia ixx="0" ixy="0" ixz="0" '
    'iyy="0.08333333333333333" iyz="0" izz="0.08333333333333333"/></inertial>'
    '<visual><origin xyz="0.5 0 0"/><geometry><box size="1.0 0.03 0.03"/></geometry></visual>'
)
PIN = '<axis xyz="0 -1 0"/><limit effort="1e6" lower="-100" upper="100" velocity="1e3"/>'


def n_four_bar_urdf(n: int) -> str:
    """The N-four-bar as URDF text (the layout of tests/fixtures/iftomm/n_four_bar.urdf, N = 2, for any N).

    Args:
        n: windows N (>= 1): N + 1 cranks at x = 0 .. N m, N couplers, each a 1 m, 1 kg thin rod.

    Returns:
        The URDF text (the plane x-z, z up; cranks vertical at home).

    Raises:
        InvalidArgument: n not an integer >= 1.
    """
    if not isinstance(n, int) or isinstance(n, bool) or n < 1:
        raise InvalidArgument("n", n, "the N-four-bar needs an integer N >= 1 of windows")
    half = repr(np.pi / 2)
    out = [
        '<?xml version="1.0"?>',
        f"<!-- IFToMM N-four-bar mechanism, N = {n}: written by mechkit.bench.iftomm.n_four_bar_urdf -->",
        f'<robot name="n_four_bar_{n}" xmlns:mechkit="https://mechkit.dev/loop">',
        '  <link name="ground"/>',
    ]
    for k in range(n + 1):
        out += [
            f'  <link name="crank{k}_link">{ROD}</link>',
            (
                f'  <joint name="crank{k}" type="revolute"><parent link="ground"/><child link="crank{k}_link"/>'
                f'<origin xyz="{k} 0 0"/>{PIN}</joint>'
            ),
            (
                f'  <link name="B{k}"/><joint name="B{k}_fixed" type="fixed"><parent link="crank{k}_link"/>'
                f'<child link="B{k}"/><origin xyz="1 0 0"/></joint>'
            ),
            f'  <mechkit:guess joint="crank{k}" value="{half}"/>',
        ]
    for k in range(1, n + 1):
        out += [
            f'  <link name="coupler{k}_link">{ROD}</link>',
            (
                f'  <joint name="coupler{k}" type="revolute"><parent link="crank{k - 1}_link"/>'
                f'<child link="coupler{k}_link"/><origin xyz="1 0 0"/>{PIN}</joint>'
            ),
            (
                f'  <link name="coupler{k}_end"/><joint name="coupler{k}_end_fixed" type="fixed">'
                f'<parent link="coupler{k}_link"/><child link="coupler{k}_end"/><origin xyz="1 0 0"/></joint>'
            ),
            f'  <mechkit:loop name="pin{k}" type="revolute" frame_a="coupler{k}_end" frame_b="B{k}" axis="0 -1 0"/>',
            f'  <mechkit:guess joint="coupler{k}" value="-{half}"/>',
        ]
    return "\n".join([*out, "</robot>", ""])


def four_bar_gain(n: int) -> float:
    """K of the N-four-bar's branch ODE theta'' = -K cos(theta) (1/s^2): N + 1 cranks of m L^2 / 3 and N
    couplers translating at L theta' make the mass m L^2 ((N + 1) / 3 + N); the weights the potential
    g m L ((N + 1) / 2 + N) sin(theta).

    Args:
        n: windows N.

    Returns:
        K (1/s^2).
    """
    return G * ((n + 1) / 2 + n) / ((n + 1) / 3 + n)


def four_bar_reference(n: int, t: np.ndarray) -> np.ndarray:
    """Crank angle (rad from +x) of the N-four-bar at times t, from vertical with B0 at +1 m/s along x.

    Args:
        n: windows N.
        t: (k,) increasing times from 0 (s).

    Returns:
        (k,) the angles (scipy DOP853 at rtol 1e-12).
    """
    k = four_bar_gain(n)
    sol = solve_ivp(
        lambda _, y: [y[1], -k * np.cos(y[0])], (0.0, t[-1]), [np.pi / 2, -1.0], "DOP853", rtol=1e-12, atol=1e-12,
        dense_output=True,
    )  # fmt: skip
    return sol.sol(t)[0]


def _skew(w: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


class BricardChart:
    """Bricard's mechanism reduced to joint O's angle, from Pinocchio's kinematics and dynamics alone.

    Args:
        model: the tree of tests/fixtures/iftomm/bricard.urdf (Pinocchio's URDF reader), joint O first.
        frame_a: the cut's frame on rod 5 (its axis the frame's x).
        frame_b: the cut's frame on the ground (axis x).
    """

    def __init__(self, model: pin.Model, frame_a: str = "rod5_end", frame_b: str = "ground_P5"):
        self.model, self.data = model, model.createData()
        self.fa, self.fb = model.getFrameId(frame_a), model.getFrameId(frame_b)
        self.guess = np.zeros(model.nq)

    def residual(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The closure and its Jacobian at q.

        Args:
            q: (nq,) the tree's pose.

        Returns:
            (6,) point a - point b (m) and axis_a x axis_b; (6, nv) their Jacobian.
        """
        m, d = self.model, self.data
        pin.computeJointJacobians(m, d, q)
        pin.updateFramePlacements(m, d)
        a_frame, b_frame = d.oMf[self.fa], d.oMf[self.fb]
        axis_a, axis_b = a_frame.rotation[:, 0], b_frame.rotation[:, 0]
        jac = pin.getFrameJacobian(m, d, self.fa, pin.LOCAL_WORLD_ALIGNED)
        r = np.concatenate([a_frame.translation - b_frame.translation, np.cross(axis_a, axis_b)])
        return r, np.vstack([jac[:3], _skew(axis_b) @ _skew(axis_a) @ jac[3:]])

    def solve(self, theta: float) -> np.ndarray:
        """The closed pose with joint O at theta: Gauss-Newton from the last pose, to 1e-15.

        Args:
            theta: joint O's angle (rad).

        Returns:
            (nq,) the pose.
        """
        q = self.guess.copy()
        q[0] = theta
        for _ in range(50):
            r, jac = self.residual(q)
            if np.max(np.abs(r)) < 1e-15:
                break
            q[1:] -= np.linalg.lstsq(jac[:, 1:], r, rcond=None)[0]
        return q

    def chart(self, theta: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The pose and its first two derivatives along the chart (5-point differences of `CHART_STEP`).

        Args:
            theta: joint O's angle (rad).

        Returns:
            (q, dq/dtheta, d2q/dtheta2), each (nq,).
        """
        h = CHART_STEP
        qs = [self.solve(theta + k * h) for k in (-2, -1, 0, 1, 2)]
        self.guess = qs[2]
        rate = (qs[0] - 8 * qs[1] + 8 * qs[3] - qs[4]) / (12 * h)
        curve = (-qs[0] + 16 * qs[1] - 30 * qs[2] + 16 * qs[3] - qs[4]) / (12 * h * h)
        return qs[2], rate, curve

    def rhs(self, _t: float, y: np.ndarray) -> list[float]:
        """The reduced Lagrange equation as a first-order ODE.

        Args:
            _t: time (s; the system is autonomous).
            y: (theta rad, theta' rad/s).

        Returns:
            (theta', theta'').
        """
        q, rate, curve = self.chart(y[0])
        mass = pin.crba(self.model, self.data, q)
        mass = np.triu(mass) + np.triu(mass, 1).T
        bias = pin.rnea(self.model, self.data, q, rate * y[1], curve * y[1] ** 2)
        return [y[1], -float(rate @ bias) / float(rate @ mass @ rate)]

    def run(self, t: np.ndarray, rtol: float = 1e-11) -> np.ndarray:
        """Released at rest at q = 0: the poses at times t (DOP853).

        Args:
            t: (k,) increasing times from 0 (s).
            rtol: DOP853's relative and absolute tolerance.

        Returns:
            (k, nq) the poses.
        """
        self.guess = np.zeros(self.model.nq)
        sol = solve_ivp(self.rhs, (0.0, t[-1]), [0.0, 0.0], "DOP853", rtol=rtol, atol=rtol, dense_output=True)
        self.guess = np.zeros(self.model.nq)
        poses = []
        for theta in sol.sol(t)[0]:  # in time order: each pose from the last, on the branch
            self.guess = self.solve(theta)
            poses.append(self.guess)
        return np.array(poses)


def flyball_reference(model: pin.Model, duration: float, rtol: float = 1e-10) -> Any:
    """The flyball governor by Pinocchio's ABA with its two spring-dampers, scipy's Radau at rtol.

    Args:
        model: the tree of tests/fixtures/iftomm/flyball_governor.urdf (joints shaft, rod_left, rod_right, s).
        duration: simulated time (s).
        rtol: Radau's relative tolerance (atol rtol / 100).

    Returns:
        scipy's solution (dense) of (rod angles, s, the 4 rates): y[2] is s (m); the shaft's angle, cyclic, left out.
    """
    data = model.createData()
    j = {name: model.getJointId(name) for name in ("s", "rod_left", "rod_right")}
    struts = [(j["s"], np.array([side * 0.05, 0, 0]), j[rod], np.array([0.5, 0, 0])) for side, rod in
              ((1, "rod_left"), (-1, "rod_right"))]  # fmt: skip
    stiffness, damping, free = 8e5, 4e4, 0.5  # N/m, N s/m, m

    def rhs(_t: float, y: np.ndarray) -> np.ndarray:
        q, v = np.concatenate([[0.0], y[:3]]), y[3:]  # the shaft's angle is cyclic: left out
        pin.forwardKinematics(model, data, q, v)
        fext = [pin.Force.Zero() for _ in range(model.njoints)]
        for ja, pa, jb, pb in struts:
            ends = []
            for jt, p in ((ja, pa), (jb, pb)):
                frame, twist = data.oMi[jt], data.v[jt]
                ends.append((frame.act(p), frame.rotation @ (twist.linear + np.cross(twist.angular, p))))
            gap = ends[1][0] - ends[0][0]
            u = gap / np.linalg.norm(gap)
            push = -stiffness * (np.linalg.norm(gap) - free) - damping * u @ (ends[1][1] - ends[0][1])
            for jt, p, f in ((jb, pb, push * u), (ja, pa, -push * u)):
                local = data.oMi[jt].rotation.T @ f
                fext[jt] += pin.Force(local, np.cross(p, local))
        acc = pin.aba(model, data, q, v, np.zeros(4), fext)
        return np.concatenate([v[1:], acc])

    y0 = np.array([np.pi / 6, np.pi / 6, 0.5, 2 * np.pi, 0.0, 0.0, 0.0])
    return solve_ivp(rhs, (0.0, duration), y0, "Radau", rtol=rtol, atol=rtol / 100, dense_output=True)


def mujoco_run(
    mech: Any, duration: float, v0: np.ndarray | None = None, edit: Any = None
) -> tuple[np.ndarray, np.ndarray, float]:
    """MuJoCo on the exported model (its timestep and RK4 unless `edit` changes them) from home at v0.

    Args:
        mech: the mechanism (`mechkit.Mechanism`); a zero diagonal moment (a thin rod's about its
            axis, a point mass's) and a zero mass become `MJ_AXIAL` in the export.
        duration: simulated time (s).
        v0: (nv,) initial joint rates (default rest).
        edit: a function changing the exported MJCF tree (`xml.etree.ElementTree.Element`) in place, or None.

    Returns:
        (times (k,) s, qpos (k, nq) = Pinocchio's q, NaN from MuJoCo's first instability warning on, CPU time
        of the mj_step loop in s).

    Raises:
        MethodUnavailable: the export refuses the model (a body MuJoCo cannot take).
    """
    import mujoco

    padded = copy.copy(mech)
    padded.model = mech.model.copy()
    for k in range(1, padded.model.njoints):
        inertia = padded.model.inertias[k]
        moments = inertia.inertia + np.diag((np.diag(inertia.inertia) < MJ_AXIAL) * MJ_AXIAL)
        padded.model.inertias[k] = pin.Inertia(max(inertia.mass, MJ_AXIAL), inertia.lever, moments)
    root = ET.fromstring(to_mjcf(padded))
    if edit is not None:
        edit(root)
    model = mujoco.MjModel.from_xml_string(ET.tostring(root, encoding="unicode"))
    data = mujoco.MjData(model)
    data.qpos[:] = mech.home_q
    if v0 is not None:
        data.qvel[:] = v0
    steps = round(duration / model.opt.timestep)
    qpos = np.empty((steps + 1, model.nq))
    qpos[0] = data.qpos
    unstable = [mujoco.mjtWarning.mjWARN_BADQPOS, mujoco.mjtWarning.mjWARN_BADQVEL, mujoco.mjtWarning.mjWARN_BADQACC]
    start = time.process_time()
    for k in range(steps):
        mujoco.mj_step(model, data)
        qpos[k + 1] = data.qpos
        if any(data.warning[w].number for w in unstable):  # MuJoCo resets a diverged state: mark it
            qpos[k + 1 :] = np.nan
            break
    return np.arange(steps + 1) * model.opt.timestep, qpos, time.process_time() - start


@dataclass(frozen=True)
class Row:
    """One problem's line on the page.

    Attributes:
        problem: the problem and its run (duration, settings).
        error: the largest error of its point over the run (m), against `reference`.
        reference: what the error is measured against.
        cpu: mechkit's CPU time of the run (s).
        steps: accepted steps.
        mujoco: MuJoCo's error (m) and CPU time (s), or a sentence saying why not.
        published: other codes' CPU times (from their pages).
    """

    problem: str
    error: float
    reference: str
    cpu: float
    steps: int
    mujoco: str
    published: str

    @property
    def passed(self) -> bool:
        """The library's high-precision criterion met."""
        return self.error <= HIGH_PRECISION


def timed(mech: Any, duration: float, **options: Any) -> tuple[Any, float]:
    """`Mechanism.simulate` without reactions, and its process CPU time (s).

    Args:
        mech: the mechanism.
        duration: simulated time (s).
        **options: `mechkit.simulation.simulate`'s.

    Returns:
        (the `SimulationResult`, CPU seconds).
    """
    start = time.process_time()
    run = mech.simulate(duration, reactions=False, **options)
    return run, time.process_time() - start


def points(model: pin.Model, qs: np.ndarray) -> np.ndarray:
    """Every joint's origin (k, njoints - 1, 3) in the world (m) at each pose of qs (k, nq).

    Args:
        model: the Pinocchio model.
        qs: (k, nq) poses.

    Returns:
        The positions (m).
    """
    data = model.createData()
    out = np.empty((len(qs), model.njoints - 1, 3))
    for k, q in enumerate(qs):
        pin.forwardKinematics(model, data, q)
        out[k] = [data.oMi[j].translation for j in range(1, model.njoints)]
    return out


def point_error(model: pin.Model, qs: np.ndarray, ref: np.ndarray) -> float:
    """Largest distance (m) between the joints' origins at poses qs and at ref (both (k, nq)).

    Args:
        model: the Pinocchio model.
        qs: (k, nq) poses.
        ref: (k, nq) reference poses.

    Returns:
        The largest distance (m).
    """
    return float(np.max(np.linalg.norm(points(model, qs) - points(model, ref), axis=2)))
