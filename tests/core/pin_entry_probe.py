"""Every Pinocchio entry point the core calls, run on descriptions given on the command line, each call
announced on stdout before it starts: the survey of `tests/core/test_pin_constraints.py` runs it in a
subprocess, so that a call that ends the process (a segmentation fault inside Pinocchio) is named by the
last line announced. A refusal (a `MechkitError`) is an answer; any other exception fails the probe.

Usage: python pin_entry_probe.py SOURCE [SOURCE ...]: a registered name or a path; NAME~swapped is the
registered mechanism with every loop's sides swapped (frame_a for frame_b, Hooke axes likewise), assembled
on the same branch; PATH::BODY fixes BODY.
"""

from __future__ import annotations

import re
import sys

import numpy as np

from mechkit import core, from_urdf, load
from mechkit.base.exceptions import MechkitError


class _State:
    """A consistent state at the home assembly: v and a close the loops (J v = 0, J a + gamma = 0), drawn
    along the free directions; tau small and drawn."""

    def __init__(self, m, rng: np.random.Generator):
        self.q = m.home_q.copy()
        J = m.closure_jacobian(self.q)
        _, sv, Vt = np.linalg.svd(J) if J.size else (None, np.zeros(0), np.eye(m.model.nv))
        null = Vt[core.numerical_rank(sv) :].T
        self.v = null @ rng.standard_normal(null.shape[1])
        gamma = m.closure_drift(self.q, self.v)
        self.a = null @ rng.standard_normal(null.shape[1]) - (np.linalg.pinv(J) @ gamma if J.size else 0.0)
        self.tau = 0.1 * rng.standard_normal(m.model.nv)


def _calls(m, s):
    """(label, call) of each entry point at the sample state s."""
    return [
        ("mobility", lambda: m.mobility(s.q)),
        ("closure_jacobian", lambda: m.closure_jacobian(s.q)),
        ("velocities", lambda: m.velocities(s.q, s.v[[m.v_index(j) for j in m.actuated]])),
        *(
            (f"forward_dynamics {method}", lambda method=method: m.forward_dynamics(s.q, s.v, s.tau, method=method))
            for method in core.FORWARD_METHODS
        ),
        ("inverse_dynamics", lambda: m.inverse_dynamics(s.q, s.v, s.a)),
        ("forward_dynamics_batch", lambda: m.forward_dynamics_batch(s.q[None], s.v[None], s.tau[None])),
        ("inverse_dynamics_batch", lambda: m.inverse_dynamics_batch(s.q[None], s.v[None], s.a[None])),
    ]


_SWAP = {"frame_a": "frame_b", "frame_b": "frame_a", "axis_a": "axis_b", "axis_b": "axis_a"}


def swapped(name: str):
    """The registered mechanism `name` with every `<mechkit:loop>`'s sides swapped, on its home branch (a
    revolute or prismatic axis reads the same in both frames of a closed cut)."""
    m = load(name)
    urdf = re.sub(
        r"<mechkit:loop [^>]*>",
        lambda loop: re.sub(r"\b(frame_a|frame_b|axis_a|axis_b)=", lambda a: _SWAP[a.group(1)] + "=", loop.group(0)),
        m.urdf,
    )
    at_home = {
        name: float(m.home_q[m.q_index(name)])
        for name in m.model.names[1:]
        if m.model.joints[m.model.getJointId(name)].nq == 1
    }
    return from_urdf(urdf, actuated=m.actuated, guess=at_home, home={j: at_home[j] for j in m.actuated})


def probe(source: str) -> None:
    """Load `source` and run every call at two sample states, announcing each."""
    path, _, fix = source.partition("::")
    print(f"BEGIN {source} load", flush=True)
    try:
        m = (
            swapped(path.removesuffix("~swapped"))
            if path.endswith("~swapped")
            else load(path, fix=[fix] if fix else None)
        )
        rng = np.random.default_rng(0)
        samples = [_State(m, rng) for _ in range(2)]
    except MechkitError as err:
        print(f"REFUSED {source} load: {err}", flush=True)
        return
    for k, s in enumerate(samples):
        for label, call in _calls(m, s):
            print(f"BEGIN {source} {label} #{k}", flush=True)
            try:
                call()
            except MechkitError as err:
                print(f"REFUSED {source} {label}: {type(err).__name__}", flush=True)
    print(f"DONE {source}", flush=True)


if __name__ == "__main__":
    with np.errstate(all="raise", under="ignore"):
        for source in sys.argv[1:]:
            probe(source)
