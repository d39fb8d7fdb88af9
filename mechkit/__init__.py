"""mechkit: closed-loop mechanisms on Pinocchio, from parameters to joint reactions."""

from mechkit.exceptions import (
    ClosureNotConverged,
    InvalidParameters,
    MalformedDescription,
    MechkitError,
    MethodUnavailable,
    SingularConfiguration,
)
from mechkit.mechanism import Mechanism, from_urdf, load
from mechkit.registry import get_spec, specs

__all__ = [
    "ClosureNotConverged",
    "InvalidParameters",
    "MalformedDescription",
    "Mechanism",
    "MechkitError",
    "MethodUnavailable",
    "SingularConfiguration",
    "from_urdf",
    "get_spec",
    "load",
    "specs",
]
