"""The values of command-line options, parsed in one place: `NAME=VALUE` pairs, comma lists of names or
numbers, and file names by their suffix. Every error is an `InvalidArgument` naming the option as typed,
the token that failed and what was expected; a name given twice is refused (the second would silently
replace the first).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

from mechkit.base.exceptions import InvalidArgument, InvalidParameters


def pair(option: str, text: str, expected: str = "NAME=VALUE", empty: bool = False) -> tuple[str, str]:
    """One `NAME=VALUE`.

    Args:
        option: the option as typed (e.g. "--set").
        text: what was given.
        expected: the form, for the error (e.g. "JOINT=VALUE").
        empty: accept an empty value (a xacro argument may be an empty string).

    Returns:
        (name, value), both stripped; the value may hold further "=" signs.

    Raises:
        InvalidArgument: no "=", an empty name, or an empty value unless `empty`.
    """
    name, sep, value = text.partition("=")
    if not sep or not name.strip() or not (empty or value.strip()):
        raise InvalidArgument(option, text, f"expected {expected}")
    return name.strip(), value.strip()


def pairs(
    option: str, texts: Sequence[str] | None, expected: str = "NAME=VALUE", empty: bool = False
) -> dict[str, str]:
    """Repeated `NAME=VALUE`s (a repeatable option), each name once.

    Args:
        option: the option as typed.
        texts: what was given (None: the option was not used).
        expected: the form, for the error.
        empty: accept empty values (`pair`).

    Returns:
        Name -> value text, in the order given.

    Raises:
        InvalidArgument: a malformed pair, or a name given twice.
    """
    out: dict[str, str] = {}
    for text in texts or ():
        name, value = pair(option, text, expected, empty)
        if name in out:
            raise InvalidArgument(option, text, f"{name!r} is given twice ({out[name]!r} and {value!r}): give it once")
        out[name] = value
    return out


def names(option: str, text: str) -> list[str]:
    """A comma list of names (joints, bodies, metrics), each once.

    Args:
        option: the option as typed.
        text: what was given.

    Returns:
        The names, stripped, in order.

    Raises:
        InvalidArgument: an empty item, or a name given twice.
    """
    out = [item.strip() for item in text.split(",")]
    if not all(out):
        raise InvalidArgument(option, text, "expected names separated by commas, none empty")
    repeated = sorted({n for n in out if out.count(n) > 1})
    if repeated:
        raise InvalidArgument(option, text, f"{', '.join(map(repr, repeated))} given twice")
    return out


def numbers(option: str, text: str, count: int | Sequence[int] | None = None, *, what: str = "") -> list[float]:
    """A comma list of finite numbers.

    Args:
        option: the option as typed.
        text: what was given.
        count: how many numbers are expected (one count, several allowed ones, or None: any).
        what: the expected form, for the error (e.g. "MU,RADIUS"); default: the count.

    Returns:
        The numbers.

    Raises:
        InvalidArgument: an item that is not a number, NaN or inf, or the wrong count.
    """
    items = text.split(",")
    counts = (count,) if isinstance(count, int) else tuple(count) if count is not None else None
    form = what or ("numbers separated by commas" if counts is None else f"{' or '.join(map(str, counts))} number(s)")
    values = []
    for item in items:
        try:
            value = float(item)
        except ValueError:
            raise InvalidArgument(option, text, f"{item.strip()!r} is not a number; expected {form}") from None
        if not math.isfinite(value):
            raise InvalidArgument(option, text, f"{item.strip()!r} is not finite; expected {form}")
        values.append(value)
    if counts is not None and len(values) not in counts:
        raise InvalidArgument(option, text, f"expected {form}: {len(values)} number(s) given")
    return values


def named_numbers(
    option: str, texts: Sequence[str] | None, expected: str = "NAME=VALUE", count: int | Sequence[int] | None = None
) -> dict[str, list[float]]:
    """Repeated `NAME=V[,V...]`s, each name once.

    Args:
        option: the option as typed.
        texts: the pairs given (None: the option was not used).
        expected: the form, for the error.
        count: how many numbers each name takes (`numbers`; None: any).

    Returns:
        Name -> its numbers.

    Raises:
        InvalidArgument: a malformed pair, a name given twice, a value that is not a finite number, the wrong
            count of numbers.
    """
    out = {}
    for name, value in pairs(option, texts, expected).items():
        try:
            out[name] = numbers(option, value, count, what=expected)
        except InvalidArgument as err:  # shown with its name, as typed
            raise InvalidArgument(option, f"{name}={value}", err.why) from None
    return out


def suffixed(option: str, path: str | None, suffixes: Sequence[str]) -> str | None:
    """A file name whose suffix says what is written, checked before any work.

    Args:
        option: the option as typed.
        path: the file name given (None: the option was not used).
        suffixes: the accepted suffixes (lower case, with their dot).

    Returns:
        The path as given.

    Raises:
        InvalidArgument: another suffix.
    """
    if path is not None and Path(path).suffix.lower() not in suffixes:
        raise InvalidArgument(option, path, f"expected a {' or '.join(suffixes)} file")
    return path


#: The library's name of an argument -> the option a command-line user types for it (names that are options).
TYPED = {
    "lock": "--lock",
    "keep": "--keep",
    "fix": "--fix",
    "freeflyer": "--freeflyer",
    "base": "--base",
    "base_inertia": "--base-inertia",
    "actuated": "--actuated",
    "grid": "--grid",
    "metric": "--metric",
    "column": "--optimise",
    "scene": "--scene",
    "samples": "--samples",
    "body": "--body",
    "law": "--law",
    "dt": "--dt",
    "method": "--method",
    "duration": "--duration",
    "q": "--q",
    "g": "--gravity",
    "n": "-n",
    "mode": "--mode",
    "point": "--point",
    "output": "-o",
    "inputs": "--at",  # a pose's input joints (stiffness, modes)
    "spring": "--spring",
    "rtol/atol/max_step": "--rtol",  # the integrator's tolerances (atol is 1e-2 rtol on the command line)
    "scheduler": "--scheduler",
    "workers": "--workers",
    "wait_workers": "--wait-workers",
    "dashboard": "--dashboard",
    "tls_ca": "--tls-ca",
    "tls_cert": "--tls-cert",
    "tls_key": "--tls-key",
}


def as_typed(err: InvalidParameters, given: set[str]) -> str:
    """An error about an argument the command line gave, told with the option as typed.

    Args:
        err: the library's error (its `name` is the library's argument).
        given: the options of the command (`--lock`, ...), so that only those are renamed.

    Returns:
        The message: "OPTION: why (got value)" where the argument is one of `given`, else the error as it is.
    """
    option = TYPED.get(err.name)
    if option is None or option not in given:
        return str(err)
    return f"{option}: {err.why} (got {err.value!r})"
