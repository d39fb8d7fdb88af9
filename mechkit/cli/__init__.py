"""The `mechkit` command line: one module per command, the only place in mechkit that prints.

A command module exposes `add_parser(sub)`, which adds its sub-parser and sets `func` (args -> None);
registering a command is one line in `COMMANDS`. Command modules import the heavy parts of mechkit
(viz, bench, ...) inside their `run`, so `mechkit list` starts fast and imports no mechanism.
"""

from __future__ import annotations

import argparse
import os
import sys
import warnings

import numpy as np

from mechkit.base.exceptions import InvalidParameters, MechkitError, MechkitWarning
from mechkit.cli import (
    bench,
    export,
    listing,
    modes,
    motion,
    option_values,
    output_guard,
    params,
    report,
    simulate,
    snapshot,
    stiffness,
    sweep,
    urdf,
    validate,
    view,
)

COMMANDS = (
    listing,
    urdf,
    report,
    snapshot,
    bench,
    export,
    params,
    sweep,
    motion,
    simulate,
    validate,
    view,
    stiffness,
    modes,
)


def build_parser() -> argparse.ArgumentParser:
    """The parser of every command in `COMMANDS`."""
    parser = argparse.ArgumentParser(prog="mechkit", description="Closed-loop mechanisms on Pinocchio.")
    sub = parser.add_subparsers(dest="command", required=True)
    for command in COMMANDS:
        command.add_parser(sub)
    return parser


#: Exit status after a broken pipe (a reader such as `head` closed standard output): 128 + SIGPIPE.
EXIT_BROKEN_PIPE = 141


def main(argv: list[str] | None = None) -> int:
    """Run one command; errors are one line on stderr and exit status 2, a broken pipe ends quietly.

    Args:
        argv: the arguments (default: the process's).

    Returns:
        The exit status: 0 done, 2 refused (one line on stderr), others as the command says (`mechkit sweep`).
    """
    args = build_parser().parse_args(argv)
    with warnings.catch_warnings():  # restores the warning printer on leaving
        warnings.simplefilter("always", MechkitWarning)
        warnings.showwarning = _warning
        return _run(args)


def _run(args: argparse.Namespace) -> int:
    """Run the parsed command (see `main`)."""
    try:
        output_guard.check(args)  # before any work: no output may be an input or another output
        with np.errstate(all="raise", under="ignore"):  # a result flushed to zero is not a failure
            args.func(args)
        sys.stdout.flush()
    except BrokenPipeError:
        # nobody reads any more: point stdout at /dev/null so the interpreter's final flush is silent
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return EXIT_BROKEN_PIPE
    except InvalidParameters as err:  # named as the user typed it
        return _error(option_values.as_typed(err, _options(args)))
    except MechkitError as err:
        return _error(str(err))
    except ArithmeticError as err:  # FloatingPointError under errstate, ZeroDivisionError in a law
        return _error(f"numerical failure ({type(err).__name__}: {err})")
    except OSError as err:
        where = f"{err.filename}: " if err.filename else ""
        return _error(f"{where}{err.strerror or err}")
    return 0


def _options(args: argparse.Namespace) -> set[str]:
    """The options of the command that ran (as typed: "--lock", "-o"), from its parser."""
    parser = build_parser()
    commands = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction)).choices
    return {s for action in commands[args.command]._actions for s in action.option_strings}


def _warning(message: Warning | str, category: type[Warning], *args: object, **kwargs: object) -> None:
    """Print a mechkit warning as one line on stderr (others as Python shows them)."""
    if issubclass(category, MechkitWarning):
        print(f"mechkit: warning: {message}", file=sys.stderr)
    else:
        _show_warning(message, category, *args, **kwargs)


_show_warning = warnings.showwarning


def _error(message: str) -> int:
    """Print the error (no traceback) and give status 2."""
    print(f"mechkit: error: {message}", file=sys.stderr)
    return 2
