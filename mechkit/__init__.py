"""mechkit: closed-loop mechanisms on Pinocchio, from parameters to joint reactions."""

from mechkit.base.exceptions import (
    ClosureNotConverged,
    InvalidParameters,
    MalformedDescription,
    MechkitError,
    MethodUnavailable,
    SingularConfiguration,
)
from mechkit.catalog.registry import get_spec, specs
from mechkit.loading import from_urdf, load
from mechkit.mechanism import Mechanism

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
