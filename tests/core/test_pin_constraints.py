"""Pinocchio's constraint API (`mechkit.core.pin_constraints`): the legacy anchors express mechkit's cuts
(on the closure manifold their rows span the kernel's: the same accelerations close both), what they
cannot express is refused, and a data serves either constraintDynamics or lcaba."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from tests_support import FIXTURES, ROOT

from mechkit import core
from mechkit.base.exceptions import MethodUnavailable
from mechkit.bench.sampling import make_samples
from mechkit.catalog.registry import ENTRIES
from mechkit.core.pin_constraints import LegacyConstraints


@pytest.mark.parametrize("name", ["four_bar", "five_bar", "parallel_2t1r", "spherical_2dof", "tetra_3rr3uru"])
def test_anchor_rows_span_the_kernel_rows_on_the_manifold(name, load_cached):
    """At assembled states, every anchor row is a combination of the kernel's full rows and the reverse
    (the same constraint), and an acceleration closing the kernel's rows closes the anchors'."""
    m = load_cached(name)
    legacy = LegacyConstraints(m.model, list(m.cuts))
    for s in make_samples(m, 2):
        legacy.dynamics(s.q, s.v, s.tau, core.proximal_settings(1e-12, 1e-9, 20))
        J_pin, gamma_pin = legacy.jacobian(), legacy.drift(legacy.jacobian().shape[0])
        J = m.closure_jacobian(s.q)
        r = np.linalg.matrix_rank
        assert (
            r(np.vstack([J, J_pin]), 1e-9 * np.abs(J).max())
            == r(J, 1e-9 * np.abs(J).max())
            == r(J_pin, 1e-9 * np.abs(J_pin).max())
        )
        a = (
            m.accelerations(s.q, s.v, s.accelerations, list(s.input_names))
            if len(s.input_names) == len(m.actuated)
            else s.a
        )
        assert np.max(np.abs(J_pin @ a + gamma_pin)) < 1e-9 * max(1.0, np.abs(J_pin).max() * np.abs(a).max())


def test_what_the_anchors_cannot_express_is_refused(load_cached):
    four = load_cached("four_bar")
    c = four.closures[0]
    hooke = core.LoopClosure(
        "H", "hooke", c.frame_a, c.frame_b, axis_a=np.array([1.0, 0, 0]), axis_b=np.array([0, 0, 1.0])
    )
    with pytest.raises(MethodUnavailable, match="hooke"):
        LegacyConstraints(four.model, list(core.ClosureModel(four.model, [hooke]).kernel.cuts))
    with pytest.raises(MethodUnavailable, match="coupling"):
        LegacyConstraints(four.model, list(four.cuts), couplings=1)


def test_one_data_serves_constraint_dynamics_or_lcaba_not_both(load_cached):
    """lcaba's joint ordering breaks constraintDynamics on the same data (measured: 0.74 relative error on
    the tetrahedral unit before the datas were separated), so each has its own."""
    m = load_cached("four_bar")
    s = make_samples(m, 1)[0]
    settings = core.proximal_settings(1e-12, 1e-9, 20)
    proximal, ordered = LegacyConstraints(m.model, list(m.cuts)), LegacyConstraints(m.model, list(m.cuts), ordered=True)
    ordered.loop_constrained_aba(s.q, s.v, s.tau, core.proximal_settings(1e-10, 1.0, 200))
    with pytest.raises(AssertionError):
        ordered.dynamics(s.q, s.v, s.tau, settings)
    with pytest.raises(AssertionError):
        proximal.loop_constrained_aba(s.q, s.v, s.tau, settings)


def test_what_dynamics_returns_is_the_caller_s_own(load_cached):
    """Pinocchio 4.1 returns constraintDynamics' accelerations and the Jacobian by value, and the
    multipliers are copied from the data's buffer: a later call at another state leaves the first
    call's arrays unchanged (the proximal wrapper returns them, with no copy of its own)."""
    m = load_cached("five_bar")
    legacy = LegacyConstraints(m.model, list(m.cuts))
    s0, s1 = make_samples(m, 2)
    settings = core.proximal_settings(1e-12, 1e-9, 20)
    first = legacy.dynamics(s0.q, s0.v, s0.tau, settings)[:3]
    kept = [x.copy() for x in first]
    second = legacy.dynamics(s1.q, s1.v, s1.tau, settings)[:3]
    for x, y, z in zip(first, kept, second):
        assert np.array_equal(x, y) and not np.array_equal(x, z) and not np.shares_memory(x, z)


PROBE = Path(__file__).with_name("pin_entry_probe.py")
GROUND_CUT = FIXTURES / "four_bar_ground_cut.urdf"


def _run(*args: str, script: str | None = None) -> subprocess.CompletedProcess:
    """A Python subprocess on this checkout (a script given as text, or the probe with its arguments)."""
    command = [sys.executable, "-c", script] if script else [sys.executable, str(PROBE), *args]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run(command, capture_output=True, text=True, env=env, cwd=ROOT, timeout=600, check=False)


def test_lcaba_with_a_loop_frame_on_the_ground_answers_and_agrees_with_kkt():
    """A four-bar cut at its rocker's ground pivot (the loop's frame_a on the ground): pin.lcaba ended the
    process there (a segmentation fault); it now answers, in a subprocess that exits cleanly, with the
    accelerations and constraint force of the dense KKT solve."""
    out = _run(
        script=(
            "import numpy as np, mechkit\n"
            f"m = mechkit.load({str(GROUND_CUT)!r})\n"
            "q = m.assemble({'crank': 0.6}); v = m.velocities(q, [1.5]); tau = np.array([0.2, 0.0, 0.0])\n"
            "a, k = (m.forward_dynamics(q, v, tau, method=x) for x in ('lcaba', 'kkt'))\n"
            "print(np.max(np.abs(a.a - k.a)) / np.max(np.abs(k.a)),"
            " np.max(np.abs(a.constraint_force - k.constraint_force)) / np.max(np.abs(k.constraint_force)))\n"
        )
    )
    assert out.returncode == 0, (out.returncode, out.stderr[-2000:])
    accelerations, forces = (float(x) for x in out.stdout.split())
    assert accelerations < 1e-8 and forces < 1e-8, out.stdout


def _field_sources() -> list[str]:
    from mechkit.bench.field import ROBOTS

    return [str(r.file(FIXTURES / "field")) + (f"::{r.fix[0]}" if r.fix else "") for r in ROBOTS]


def test_no_pinocchio_entry_point_ends_the_process():
    """The survey: every entry point of the core into Pinocchio (mobility, closure Jacobian, velocities, the
    four forward-dynamics methods, inverse dynamics, both batches) on every registered mechanism, the same
    with every loop's sides swapped, the four-bar cut at its ground pivot and the field's robots, in one
    subprocess that announces each call before it starts: the process must end cleanly (a refusal by name
    is an answer), and a crash is reported by the call that caused it."""
    names = [e.name for e in ENTRIES]
    sources = [*names, *(f"{n}~swapped" for n in names), str(GROUND_CUT), str(FIXTURES / "pendulum.urdf")]
    sources += _field_sources()
    out = _run(*sources)
    announced = [line for line in out.stdout.splitlines() if line.startswith("BEGIN ")]
    assert out.returncode == 0, (
        f"exit {out.returncode} during {announced[-1] if announced else 'start'}: {out.stderr[-2000:]}"
    )
    done = [line.split(" ", 1)[1] for line in out.stdout.splitlines() if line.startswith("DONE ")]
    # every registered mechanism and its swapped twin ran every call (the deployable's twin does not assemble)
    assert set(names) | {f"{n}~swapped" for n in names if n != "deployable_9rr12uru"} <= set(done), out.stdout
    assert str(GROUND_CUT) in done
