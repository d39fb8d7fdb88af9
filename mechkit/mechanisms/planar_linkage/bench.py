"""Bench methods and references of the planar calibration linkages four_bar and five_bar.

Their independent methods live in `mechkit.validation` (numpy only); a linkage declares them on its
`SPEC` with `bench_methods(motion)` and `bench_references(motion)`, `motion` being its closed form
(`state.Motion`):

- references: the closed form (circle intersection) for assembly, its accelerations with the
  efforts of planar Newton-Euler for forward dynamics, planar Newton-Euler for inverse dynamics;
- assembly: the closed form;
- forward dynamics: Lagrange's equations of the first kind in reference-point coordinates
  (`lagrange.lagrange_forward`), the efforts on the motor pins;
- inverse dynamics: planar Newton-Euler, classic virtual work over the URDF coordinates
  (`validation.planar_soc.whole_skc`, efforts only), sequential SOC virtual work
  (`validation.planar_soc.soc_skcs`: the dyad at the cut first, then single links) and Lagrange's
  equations of the first kind (`lagrange.lagrange_first_kind`, the ten-bar patent's A f = P).

The numpy methods start from the link motion (the closed-form `LinkageState` of the sample, cached
in `sample.extra`), not from (q, v, a): their times exclude that conversion.
"""

from __future__ import annotations

from functools import partial
from typing import Any

import numpy as np

from mechkit.catalog.contract import BenchMethod, BenchReference
from mechkit.mechanism import Mechanism
from mechkit.mechanisms.planar_linkage.lagrange import lagrange_first_kind, lagrange_forward
from mechkit.mechanisms.planar_linkage.state import Motion, at_rest, joint_vector, state
from mechkit.validation import planar_newton_euler
from mechkit.validation.planar_soc import soc_skcs, whole_skc
from mechkit.validation.soc import SOCResult, classic_virtual_work, solve_soc


def closed_form_q(motion: Motion, mech: Mechanism, sample: Any) -> np.ndarray:
    """Assembly by circle intersection, as a mechkit q (rad).

    Args:
        motion: the linkage's closed form.
        mech: the linkage.
        sample: a bench sample (inputs, rates, accelerations in actuated order; tau; `extra` for the cache).

    Returns:
        q (nq,).
    """
    st = at_rest(motion, mech, sample)
    return joint_vector(mech, st, st.q)


def closed_form_a(motion: Motion, mech: Mechanism, sample: Any) -> np.ndarray:
    """The closed form's joint accelerations (rad/s^2), as a mechkit (nv,) vector.

    Args:
        motion: the linkage's closed form.
        mech: the linkage.
        sample: a bench sample (inputs, rates, accelerations in actuated order; tau; `extra` for the cache).

    Returns:
        a (nv,).
    """
    st = state(motion, mech, sample)
    return joint_vector(mech, st, st.qdd)


def newton_euler(motion: Motion, mech: Mechanism, sample: Any) -> planar_newton_euler.PlanarDynamics:
    """Planar Newton-Euler: efforts and every pin's reaction.

    Args:
        motion: the linkage's closed form.
        mech: the linkage.
        sample: a bench sample (inputs, rates, accelerations in actuated order; tau; `extra` for the cache).

    Returns:
        Efforts (N m) and every pin's reaction (world wrench (6,)).
    """
    return planar_newton_euler.newton_euler(state(motion, mech, sample))


def classic(motion: Motion, mech: Mechanism, sample: Any) -> dict[str, Any]:
    """Classic virtual work over the URDF coordinates: efforts only.

    Args:
        motion: the linkage's closed form.
        mech: the linkage.
        sample: a bench sample (inputs, rates, accelerations in actuated order; tau; `extra` for the cache).

    Returns:
        {"efforts": actuated joint -> torque (N m)}.
    """
    return {"efforts": classic_virtual_work(whole_skc(state(motion, mech, sample)))}


def soc(motion: Motion, mech: Mechanism, sample: Any) -> SOCResult:
    """Sequential SOC virtual work (`validation.soc.solve_soc`): efforts and in-plane pin forces.

    Args:
        motion: the linkage's closed form.
        mech: the linkage.
        sample: a bench sample (inputs, rates, accelerations in actuated order; tau; `extra` for the cache).

    Returns:
        Efforts (N m) and every pin's reaction (world wrench (6,), in-plane forces).
    """
    return solve_soc(soc_skcs(state(motion, mech, sample)))


def bench_methods(motion: Motion) -> tuple[BenchMethod, ...]:
    """The linkage's own methods in `mechkit bench`, for its closed form `motion`.

    Args:
        motion: the linkage's closed form.

    Returns:
        The methods (assembly, forward dynamics by Lagrange, inverse dynamics by Lagrange, SOC and classic virtual
            work).
    """
    return (
        BenchMethod("closed form (circle intersection, numpy)", "assembly", partial(closed_form_q, motion)),
        BenchMethod(
            "Lagrange first kind, forward (numpy, from link motion)",
            "forward_dynamics",
            partial(lagrange_forward, motion),
        ),
        BenchMethod("planar Newton-Euler (numpy, from link motion)", "inverse_dynamics", partial(newton_euler, motion)),
        BenchMethod("classic virtual work (numpy, from link motion)", "inverse_dynamics", partial(classic, motion)),
        BenchMethod("sequential SOC virtual work (numpy, from link motion)", "inverse_dynamics", partial(soc, motion)),
        BenchMethod(
            "Lagrange first kind (numpy, from link motion)", "inverse_dynamics", partial(lagrange_first_kind, motion)
        ),
    )


def bench_references(motion: Motion) -> tuple[BenchReference, ...]:
    """The linkage's references in `mechkit bench` (independent of Pinocchio), for its closed form `motion`.

    Args:
        motion: the linkage's closed form.

    Returns:
        The references: the closed form for assembly, its accelerations for forward dynamics, planar Newton-Euler
            for inverse dynamics.
    """
    return (
        BenchReference("closed form (circle intersection)", "assembly", partial(closed_form_q, motion)),
        BenchReference(
            "closed-form a, tau from planar Newton-Euler", "forward_dynamics", partial(closed_form_a, motion)
        ),
        BenchReference("planar Newton-Euler (numpy)", "inverse_dynamics", partial(newton_euler, motion)),
    )
