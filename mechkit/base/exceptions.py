"""Errors raised by mechkit. Every error carries the data that explains it; none is printed."""

from __future__ import annotations


class MechkitError(Exception):
    """Base class of every error mechkit raises on purpose."""


class InvalidParameters(MechkitError):
    """A parameter value is unknown, out of range, or makes the linkage impossible.

    Attributes:
        name: the parameter's name.
        value: the offending value.
        why: the reason, in words.
    """

    def __init__(self, name: str, value: object, why: str):
        self.name, self.value, self.why = name, value, why
        super().__init__(f"parameter {name!r} = {value!r}: {why}")


class MalformedDescription(MechkitError):
    """A URDF / xacro / loop declaration is invalid.

    Attributes:
        where: the element, frame or file at fault.
        why: the reason, in words.
    """

    def __init__(self, where: str, why: str):
        self.where, self.why = where, why
        super().__init__(f"{where}: {why}")


class ClosureNotConverged(MechkitError):
    """The loop-closure solve did not reach its tolerance (the linkage may not assemble).

    Attributes:
        residual: final closure residual norm (m, rad mixed as declared rows).
        tol: requested tolerance.
        iters: iterations performed.
    """

    def __init__(self, residual: float, tol: float, iters: int, detail: str = ""):
        self.residual, self.tol, self.iters = residual, tol, iters
        msg = f"loop closure did not converge: residual {residual:.3e} > tol {tol:.1e} after {iters} iterations"
        super().__init__(msg + (f" ({detail})" if detail else ""))


class SingularConfiguration(MechkitError):
    """A linear system of the kinematics or dynamics is singular at this configuration.

    Attributes:
        cond: condition number (inf when exactly singular).
        what: which system was singular.
    """

    def __init__(self, cond: float, what: str):
        self.cond, self.what = cond, what
        condition = f"condition number {cond:.3e}" if cond < float("inf") else "no finite condition number"
        super().__init__(f"singular configuration: {what} ({condition})")


class ConstraintViolated(MechkitError):
    """A dynamics result violates the closure at acceleration level, J a + gamma = 0, beyond tolerance.

    Attributes:
        residual: max |J a + gamma| (m/s^2 for position rows).
        limit: the tolerance it exceeds.
        what: which method produced it.
    """

    def __init__(self, residual: float, limit: float, what: str):
        self.residual, self.limit, self.what = residual, limit, what
        super().__init__(f"{what}: the accelerations violate J a + gamma = 0 by {residual:.3e} (limit {limit:.1e})")


class InconsistentMotion(MechkitError):
    """No rigid answer exists: a right-hand side leaves the range of the closure rows (e.g. a velocity
    that moves along a freedom existing only instantaneously, whose drift gamma no acceleration cancels).

    Attributes:
        outside: size of the part outside the range (the least-squares residual).
        limit: the tolerance it exceeds.
        what: which equation, in words.
    """

    def __init__(self, outside: float, limit: float, what: str):
        self.outside, self.limit, self.what = outside, limit, what
        super().__init__(f"no rigid answer: {what} (outside the range by {outside:.3e}, limit {limit:.1e})")


class OutsideLimits(MechkitError):
    """An assembly whose branch leaves a joint's limits (no whole turn brings the angle back in).

    Attributes:
        joint: the joint's name.
        value: its value (rad or m).
        lower, upper: its limits (rad or m).
        where: which assembly, and how it was reached.
    """

    def __init__(self, joint: str, value: float, lower: float, upper: float, where: str):
        self.joint, self.value, self.lower, self.upper, self.where = joint, value, lower, upper, where
        super().__init__(
            f"{where}: joint {joint!r} at {value:.6g} is outside its limits [{lower:.6g}, {upper:.6g}] "
            "(the branch leaves them)"
        )


class MethodUnavailable(MechkitError):
    """A method cannot handle this mechanism (say which and why; another method can).

    Attributes:
        method: the method's name.
        why: the reason, in words.
    """

    def __init__(self, method: str, why: str):
        self.method, self.why = method, why
        super().__init__(f"{method} unavailable: {why}")


class InvalidArgument(InvalidParameters):
    """An argument of a call is malformed: wrong shape or type, not finite, out of range.

    Attributes:
        name: the argument's name.
        value: the offending value (summarised for arrays).
        why: the reason, in words.
    """

    def __init__(self, name: str, value: object, why: str):
        MechkitError.__init__(self, f"argument {name!r}: {why} (got {_summary(value)})")
        self.name, self.value, self.why = name, value, why


class UnknownOption(InvalidArgument):
    """An option's value is not one of the names it accepts.

    Attributes:
        name: the option's name; value: what was given; choices: the accepted names.
    """

    def __init__(self, name: str, value: object, choices: tuple[str, ...]):
        self.choices = tuple(choices)
        super().__init__(name, value, f"expected one of {', '.join(map(repr, self.choices))}")


class OutputError(MechkitError):
    """An output file cannot be written (refused, or the system said no); nothing was left half-written.

    Attributes:
        path: the output as given.
        why: the reason, in words.
    """

    def __init__(self, path: object, why: str):
        self.path, self.why = path, why
        super().__init__(f"output {str(path)!r}: {why}")


class MotionFailed(MechkitError):
    """No sample of a motion study succeeded: the mechanism cannot follow the motion at all.

    Attributes:
        failures: (t (s), why) of every sample, in time order.
    """

    def __init__(self, failures: list[tuple[float, str]]):
        self.failures = list(failures)
        t, why = self.failures[0]
        super().__init__(f"no sample of the motion succeeded; at t = {t:.6g} s: {why}")


class ExternalToolFailed(MechkitError):
    """A program mechkit runs (headless Chromium, the meshcat server) failed or stopped answering.

    Attributes:
        tool: the program.
        why: what it did, in words (with its last output lines where there are some).
    """

    def __init__(self, tool: str, why: str):
        self.tool, self.why = tool, why
        super().__init__(f"{tool}: {why}")


class SelfCheckFailed(MechkitError):
    """A mechanism disagrees with itself or its sources: self-checks above their threshold.

    Attributes:
        failing: check name -> value (worst residual or relative error; nan counts as failing).
        limit: the threshold.
    """

    def __init__(self, name: str, failing: dict[str, float], limit: float):
        self.failing, self.limit = dict(failing), limit
        listed = "; ".join(f"{k} = {v:.3e}" for k, v in failing.items())
        super().__init__(f"{name}: {len(failing)} self-check(s) above {limit:g}: {listed}")


def _summary(value: object) -> str:
    """A short text of a value for an error message (arrays by shape and dtype)."""
    shape = getattr(value, "shape", None)
    if shape is not None and getattr(value, "size", 0) > 6:
        return f"{type(value).__name__} of shape {tuple(shape)}, dtype {getattr(value, 'dtype', '?')}"
    text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."


class MechkitWarning(UserWarning):
    """Base class of the warnings mechkit gives on purpose (the command line prints each as one line)."""


class IgnoredClosure(MechkitWarning):
    """An element that closes a loop in another tool was left out, as the caller asked; the message names it,
    its file and line, and the mobility the model is left with."""


class MuJoCoWarning(MechkitWarning):
    """MuJoCo warned while compiling an MJCF file (what it said, with the file's name)."""
