"""Charts of the base studies (matplotlib on Agg, `mechkit.base.plotting`): the isolation chart and a held
motion's inputs and efforts."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from mechkit.base.plotting import pyplot, save_figure
from mechkit.bases.held_motion import HeldMotion
from mechkit.bases.isolation import IsolationPoint, servo_theory
from mechkit.mechanism import Mechanism


def isolation_chart(points: Sequence[IsolationPoint], path: str | Path, title: str = "", damping: float = 0.7) -> Path:
    """Residual tilt over carrier tilt against frequency, one curve per servo bandwidth, with the linear
    servo's |1 - H(jw)| dashed.

    Args:
        points: the simulated points (`mechkit.bases.isolation.isolation_point`).
        path: the file (.png or .svg).
        title: the chart's title.
        damping: the servos' damping ratio (for the dashed lines).

    Returns:
        The path written.
    """
    plt = pyplot("isolation charts")
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for k, bandwidth in enumerate(sorted({p.bandwidth for p in points})):
        mine = sorted((p for p in points if p.bandwidth == bandwidth), key=lambda p: p.frequency)
        f = np.array([p.frequency for p in mine])
        ax.loglog(f, [p.ratio for p in mine], "o-", color=f"C{k}", label=f"simulated, servos {bandwidth:g} Hz")
        dense = np.geomspace(f.min(), f.max(), 200)
        ax.loglog(dense, [servo_theory(x, bandwidth, damping) for x in dense], "--", color=f"C{k}", lw=0.8)
    ax.set_xlabel("carrier frequency (Hz)")
    ax.set_ylabel("residual tilt / carrier tilt")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(title="dashed: linear servo |1 - H|", fontsize=8)
    ax.set_title(title, fontsize=9)
    return save_figure(fig, path)


def held_chart(held: HeldMotion, path: str | Path, title: str = "") -> Path:
    """A held motion: the holding inputs, the motors' efforts and the carrier's force and moment in time.

    Args:
        held: the held motion (`mechkit.bases.held_motion.held_motion`).
        path: the file (.png or .svg).
        title: the chart's title.

    Returns:
        The path written.
    """
    from mechkit.bases.carrier import CARRIER_JOINT

    plt = pyplot("held-motion charts")
    r = held.study
    fig, axes = plt.subplots(3, 1, figsize=(6.4, 6.4), sharex=True)
    for k, name in enumerate(held.names):
        axes[0].plot(r.t, np.degrees(held.inputs[:, k]), label=name)
        axes[1].plot(r.t, r.effort(name), label=name)
    wrench = r.reactions[:, list(r.joints).index(CARRIER_JOINT)]
    for k, label in enumerate(("fx", "fy", "fz", "mx", "my", "mz")):
        axes[2].plot(r.t, wrench[:, k], label=f"{label} ({'N' if k < 3 else 'N m'})")
    axes[0].set_ylabel("input (deg)")
    axes[1].set_ylabel("motor torque (N m)")
    axes[2].set_ylabel("carrier wrench")
    axes[2].set_xlabel("t (s)")
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, ncol=3)
    axes[0].set_title(title, fontsize=9)
    return save_figure(fig, path)


def floating_chart(
    floating: Mechanism, orbit: Any, ground: Any, joints: Sequence[str], path: str | Path, title: str = ""
) -> Path:
    """A motion on a floating base beside the same on the ground: the base's rotation angle and the
    efforts of some joints in both.

    Args:
        floating: the mechanism on its floating base (`with_base`).
        orbit: its simulation (`mechkit.simulation.SimulationResult`).
        ground: the same motion's simulation on the fixed base.
        joints: the driven joints whose efforts are drawn.
        path: the file (.png or .svg).
        title: the chart's title.

    Returns:
        The path written.
    """
    import pinocchio as pin

    from mechkit.bases.carrier import FLOATING_JOINT

    plt = pyplot("floating-base charts")
    k = floating.q_index(FLOATING_JOINT)
    start = pin.Quaternion(orbit.motion.q[0, k + 3 : k + 7]).matrix()
    angle = [np.linalg.norm(pin.log3(pin.Quaternion(q[k + 3 : k + 7]).matrix() @ start.T)) for q in orbit.motion.q]
    fig, axes = plt.subplots(2, 1, figsize=(6.4, 5.2), sharex=True)
    axes[0].plot(orbit.t, np.degrees(angle))
    axes[0].set_ylabel("bus rotation (deg)")
    for n, joint in enumerate(joints):
        axes[1].plot(orbit.t, orbit.motion.effort(joint), color=f"C{n}", label=f"{joint} in orbit")
        axes[1].plot(ground.t, ground.motion.effort(joint), "--", color=f"C{n}", label=f"{joint} on the ground, 1 g")
    axes[1].set_ylabel("motor torque (N m)")
    axes[1].set_xlabel("t (s)")
    for ax in axes:
        ax.grid(True, alpha=0.3)
    axes[1].legend(fontsize=7, ncol=2)
    axes[0].set_title(title, fontsize=9)
    return save_figure(fig, path)


def efforts_chart(runs: dict[str, Any], joints: Sequence[str], path: str | Path, title: str = "") -> Path:
    """Some joints' efforts along several runs of one motion (a bench beside a flight), one line style per run.

    Args:
        runs: label -> motion study or simulation history (`mechkit.history.MotionResult`).
        joints: the joints whose efforts are drawn.
        path: the file (.png or .svg).
        title: the chart's title.

    Returns:
        The path written.
    """
    plt = pyplot("effort charts")
    fig, ax = plt.subplots(figsize=(6.4, 3.6))
    for style, (label, r) in zip(("-", "--", ":", "-."), runs.items()):
        for n, joint in enumerate(joints):
            ax.plot(r.t, r.effort(joint), style, color=f"C{n}", label=f"{joint}, {label}")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("effort (N or N m)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    ax.set_title(title, fontsize=9)
    return save_figure(fig, path)
