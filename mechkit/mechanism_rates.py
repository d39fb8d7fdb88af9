"""`MechanismRates`: a mechanism's velocities and accelerations from its inputs.

The joint velocities (J v = 0) and accelerations (J a + gamma = 0) that given input rates and
accelerations determine, one sample or N at once, and the second-order test of a velocity (whether it
is a motion of the mechanism beyond the first order); one core function per quantity, over the closure
model and a data it shares with the mechanism's other parts, with joints by name through a `JointNaming`.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from mechkit import core
from mechkit.base import arguments
from mechkit.mechanism_naming import Inputs, JointNaming


class MechanismRates:
    """Velocities and accelerations from the inputs.

    Args:
        naming: the mechanism's joints by name (`JointNaming`).
        closure_model: the tree with its closures, couplings and actuation (`mechkit.core.ClosureModel`).
        closure_data: a data of it (scratch).
    """

    def __init__(self, naming: JointNaming, closure_model: core.ClosureModel, closure_data: Any):
        self.naming, self.closure_model, self.closure_data = naming, closure_model, closure_data

    # ---------------------------------------------------------------- velocities and accelerations
    def velocities(
        self, q: np.ndarray, input_rates: Inputs, inputs: Sequence[str] | None = None, *, allow_singular: bool = False
    ) -> np.ndarray:
        """Joint velocities from the input rates, J v = 0.

        Args:
            q: (nq,) an assembled configuration.
            input_rates: joint name -> rate (rad/s or m/s; a ball joint's (3,) angular velocity), or
                rates in the order of `inputs`.
            inputs: the joints whose rates are given (default: the actuated ones).
            allow_singular: answer where the inputs do not determine the motion (then `singularity(q)`
                tells how far to trust it).

        Returns:
            (nv,) the joint velocities.

        Raises:
            SingularConfiguration: the inputs do not determine the motion to what the closure resolves.
            InvalidParameters: rates in input order on an unactuated mechanism, an unknown joint.
        """
        allow_singular = arguments.flag("allow_singular", allow_singular)
        (q,) = self.naming.one(q=q)
        split, rates = self.naming.given(
            input_rates, self.naming.input_names(inputs, "velocities from input rates"), "input_rates"
        )
        return core.velocities(self.closure_model, self.closure_data, q, split, rates, allow_singular=allow_singular)

    def velocities_batch(
        self, q: np.ndarray, input_rates: Inputs, inputs: Sequence[str] | None = None, *, allow_singular: bool = False
    ) -> np.ndarray:
        """`velocities` of N samples at once (the same numbers).

        Args:
            q: (N, nq) assembled configurations.
            input_rates: (N, k) rates in the order of `inputs`, or joint name -> (N,) (a ball joint's
                (N, 3)).
            inputs: the joints whose rates are given (default: the actuated ones).
            allow_singular: as `velocities`.

        Returns:
            (N, nv) the joint velocities.
        """
        allow_singular = arguments.flag("allow_singular", allow_singular)
        (q,) = self.naming.many(q=q)
        split, rates = self.naming.given_batch(
            input_rates, self.naming.input_names(inputs, "velocities from input rates"), len(q), "input_rates"
        )
        return core.velocities_batch(
            self.closure_model, self.closure_data, q, split, rates, allow_singular=allow_singular
        )

    def accelerations(
        self,
        q: np.ndarray,
        v: np.ndarray,
        input_accelerations: Inputs,
        inputs: Sequence[str] | None = None,
        *,
        allow_singular: bool = False,
        least_squares: bool = False,
    ) -> np.ndarray:
        """Joint accelerations from the input accelerations, J a + gamma = 0.

        Args:
            q: (nq,) an assembled configuration.
            v: (nv,) joint velocities with J v = 0.
            input_accelerations: joint name -> acceleration (rad/s^2 or m/s^2), or values in the
                order of `inputs`.
            inputs: the joints whose accelerations are given (default: the actuated ones).
            allow_singular: as `velocities`.
            least_squares: where gamma leaves the range of J, the least-squares a (minimum
                |J a + gamma|) instead of an error.

        Returns:
            (nv,) the joint accelerations.

        Raises:
            InconsistentMotion: gamma leaves the range of J (v is not a motion of the mechanism at
                second order).
            SingularConfiguration: the inputs do not determine the motion.
        """
        allow_singular = arguments.flag("allow_singular", allow_singular)
        least_squares = arguments.flag("least_squares", least_squares)
        q, v = self.naming.one(q=q, v=v)
        names = self.naming.input_names(inputs, "accelerations from input accelerations")
        split, acc = self.naming.given(input_accelerations, names, "input_accelerations")
        return core.accelerations(
            self.closure_model,
            self.closure_data,
            q,
            v,
            split,
            acc,
            allow_singular=allow_singular,
            least_squares=least_squares,
        )

    def accelerations_batch(
        self,
        q: np.ndarray,
        v: np.ndarray,
        input_accelerations: Inputs,
        inputs: Sequence[str] | None = None,
        *,
        allow_singular: bool = False,
        least_squares: bool = False,
    ) -> np.ndarray:
        """`accelerations` of N samples at once (the same numbers).

        Args:
            q: (N, nq) assembled configurations.
            v: (N, nv) joint velocities.
            input_accelerations: (N, k) values in the order of `inputs`, or joint name -> (N,).
            inputs: the joints whose accelerations are given (default: the actuated ones).
            allow_singular: as `velocities`.
            least_squares: as `accelerations`.

        Returns:
            (N, nv) the joint accelerations.
        """
        allow_singular = arguments.flag("allow_singular", allow_singular)
        least_squares = arguments.flag("least_squares", least_squares)
        q, v = self.naming.many(q=q, v=v)
        names = self.naming.input_names(inputs, "accelerations from input accelerations")
        split, acc = self.naming.given_batch(input_accelerations, names, len(q), "input_accelerations")
        return core.accelerations_batch(
            self.closure_model,
            self.closure_data,
            q,
            v,
            split,
            acc,
            allow_singular=allow_singular,
            least_squares=least_squares,
        )

    # ---------------------------------------------------------------- at second order
    def second_order_inconsistency(self, q: np.ndarray, v: np.ndarray) -> float:
        """How far a velocity is from being a motion of the mechanism at second order.

        Args:
            q: (nq,) an assembled configuration.
            v: (nv,) joint velocities with J v = 0.

        Returns:
            min over a of max |J a + gamma|: 0 (to rounding) for a motion at second order.
        """
        return core.second_order_inconsistency(self.closure_model, self.closure_data, *self.naming.one(q=q, v=v))

    def second_order_velocity(self, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        """The velocity near v along which the motion continues at second order.

        Args:
            q: (nq,) an assembled configuration.
            v: (nv,) joint velocities.

        Returns:
            (nv,) a velocity with J v = 0 and gamma(q, v) in the range of J.

        Raises:
            InconsistentMotion: no such velocity near v.
        """
        return core.second_order_velocity(self.closure_model, self.closure_data, *self.naming.one(q=q, v=v))
