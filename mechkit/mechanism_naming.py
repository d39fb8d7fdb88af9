"""`JointNaming`: a mechanism's joints and actuators by name, and the arguments a user gives checked.

Joint ids, indices and values by name; the actuators' names (a URDF transmission's name stands for the
joint it drives); values given by name or in input order (any joint type, one sample or N) turned into
the joints they fix and the vectors the core takes; state arrays of one sample or of N checked by name.
It needs the closure model (its tree and actuators) and the tree's URDF text, nothing else.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from functools import cached_property
from typing import Any

import numpy as np
import pinocchio as pin

from mechkit import actuator_names, core
from mechkit.base import arguments, joint_arguments
from mechkit.base.exceptions import InvalidParameters

Inputs = Mapping[str, float | Sequence[float]] | Sequence[float] | np.ndarray


class JointNaming:
    """The joints and actuators of a mechanism by name.

    Args:
        name: the mechanism's name (named in errors).
        closure_model: the tree with its closures, couplings and actuation (`mechkit.core.ClosureModel`).
        urdf: the tree's URDF text, whose transmissions name actuators (None: none).

    Attributes:
        model: the Pinocchio model of the tree.
        actuated: the actuators, in effort order.
        sizes: state name -> its length (q: nq; v, a, tau: nv).
    """

    def __init__(self, name: str, closure_model: core.ClosureModel, urdf: str | None = None):
        self.name, self.closure_model, self.urdf = name, closure_model, urdf
        self.model, self.actuated = closure_model.model, closure_model.actuated
        nv = self.model.nv
        self.sizes = {"q": self.model.nq, "v": nv, "a": nv, "tau": nv}

    @cached_property
    def aliases(self) -> dict[str, str]:
        """The URDF's transmission names -> the joints they drive (parsed at first use)."""
        return actuator_names.transmission_names(self.urdf)

    # ---------------------------------------------------------------- joints by name
    def joint_id(self, joint: str) -> int:
        """Pinocchio id of a joint.

        Args:
            joint: the joint's name.

        Returns:
            Its id in `model` (1 for the first joint; 0 is the universe).

        Raises:
            InvalidParameters: no such joint (the message names the joints).
        """
        return self.closure_model.joint_id(joint)

    def q_index(self, joint: str) -> int:
        """Index of a joint's first coordinate in q.

        Args:
            joint: the joint's name.

        Returns:
            The index into q (nq,).
        """
        return self.model.joints[self.joint_id(joint)].idx_q

    def v_index(self, joint: str) -> int:
        """Index of a joint's first velocity coordinate in v.

        Args:
            joint: the joint's name.

        Returns:
            The index into v, a and tau (nv,).
        """
        return self.model.joints[self.joint_id(joint)].idx_v

    def neutral(self) -> np.ndarray:
        """Pinocchio's neutral configuration (nq,) of the tree (every joint at zero; loops open)."""
        return pin.neutral(self.model)

    def joint_values(self, q: np.ndarray) -> dict[str, float | np.ndarray]:
        """Every joint's value at a configuration.

        Args:
            q: (nq,) the configuration.

        Returns:
            Joint name -> value (rad or m; a ball joint's rotation vector (3,), see `mechkit.core.joints`).
        """
        return core.joint_values(self.model, q)

    def require_actuators(self, what: str) -> None:
        """Refuse a computation that needs actuators on a mechanism that declares none.

        Args:
            what: the computation, named in the error.

        Raises:
            InvalidParameters: the mechanism is unactuated.
        """
        if not self.actuated:
            raise InvalidParameters(
                "actuated",
                (),
                f"{self.name} is unactuated (its file declares no "
                f"<transmission>, name_mot or MJCF actuator): {what} needs actuators; "
                "pass actuated=[...] (command line: --actuated J1,J2)",
            )

    # ---------------------------------------------------------------- arguments given by name
    def values(self, values: Inputs | None, names: Sequence[str], arg: str) -> dict[str, Any]:
        """Joint values by name, checked: a mapping (joints or actuators) or values in the order of `names`.

        Args:
            values: name -> value (rad or m; a ball joint's rotation vector), values in the order of
                `names`, or None (no value).
            names: the joints or actuators that values given in order are for.
            arg: the argument's name, named in errors.

        Returns:
            Joint name -> value (an actuator's value carried to the joint it drives).
        """
        if values is None:
            return {}
        if not isinstance(values, Mapping) and not names:
            self.require_actuators(f"{arg} given in actuated order")
        sizes = {n: core.joint_size(self.model, self.joint_id(n)) for n in names if self.model.existJointName(n)}
        known = actuator_names.known_names(self.closure_model, self.aliases)
        if isinstance(values, Mapping):
            actuator_names.check_known(self.closure_model, arg, values, self.aliases)
        return actuator_names.to_joints(
            self.closure_model, arg, joint_arguments.joint_values(arg, values, names, known, sizes), self.aliases
        )

    def input_names(self, inputs: Sequence[str] | None, what: str) -> list[str]:
        """The given input joints or actuators, checked (default: the actuated ones, which must exist).

        Args:
            inputs: joint or actuator names, or None (the actuated ones).
            what: the computation, named in the error when there is no actuator.

        Returns:
            The names.
        """
        if inputs is None:
            self.require_actuators(what)
            return list(self.actuated)
        actuator_names.check_known(self.closure_model, "inputs", inputs, self.aliases)
        return joint_arguments.joint_names(
            "inputs", inputs, actuator_names.known_names(self.closure_model, self.aliases)
        )

    def input_joints(self, names: Sequence[str]) -> list[str]:
        """The joints that input names (joints or actuators, checked) fix.

        Args:
            names: joint or actuator names.

        Returns:
            The joints' names.
        """
        return actuator_names.to_joint_names(self.closure_model, "inputs", names, self.aliases)

    def given(self, values: Inputs, names: Sequence[str], arg: str) -> tuple[core.InputSplit, np.ndarray]:
        """The split of the given joints and their values as one vector.

        Args:
            values: as `values`.
            names: as `values`.
            arg: as `values`.

        Returns:
            The split of the joints given (`core.InputSplit`) and their values (k,), aligned with its
            `input_v` (the velocity slots of the joints, in the order given).
        """
        given = self.values(values, names, arg)
        split = self.closure_model.split(tuple(given))
        return split, np.concatenate(
            [np.atleast_1d(np.asarray(x, dtype=float)) for x in given.values()] or [np.zeros(0)]
        )

    def given_batch(self, values: Inputs, names: Sequence[str], n: int, arg: str) -> tuple[core.InputSplit, np.ndarray]:
        """The split of the given joints and their values for N samples.

        Args:
            values: (n, k) values in the order of `names`, or name -> (n,) (a ball joint's (n, 3)).
            names: the joints or actuators that values given in order are for.
            n: the number of samples.
            arg: the argument's name, named in errors.

        Returns:
            The split of the joints given (`core.InputSplit`) and their values (n, k), columns aligned
            with its `input_v`.
        """
        sizes = {j: core.joint_size(self.model, self.joint_id(j)) for j in self.model.names[1:]}
        known = actuator_names.known_names(self.closure_model, self.aliases)
        keys, given = joint_arguments.sample_inputs(arg, values, names, n, known, sizes)
        scale = actuator_names.to_joints(self.closure_model, arg, dict.fromkeys(keys, 1.0), self.aliases)  # actuators
        given = given * np.repeat(list(scale.values()), [sizes[j] for j in scale])
        return self.closure_model.split(tuple(scale)), given

    def one(self, **values: Any) -> list[np.ndarray]:
        """State arrays of one sample, checked by name.

        Args:
            **values: q (nq,), v, a or tau (nv,), by name.

        Returns:
            The arrays as floats, in the order given.
        """
        return arguments.sample(self.sizes, **values)

    def many(self, **values: Any) -> list[np.ndarray]:
        """State arrays of N samples, checked by name, one N for all.

        Args:
            **values: q (N, nq), v, a or tau (N, nv), by name.

        Returns:
            The arrays as floats, in the order given.
        """
        return arguments.samples(self.sizes, **values)
