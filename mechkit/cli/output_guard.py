"""Outputs never touch inputs: before a command does any work, every file it will write is resolved (symlinks
followed) and compared with every file it reads (the description, its sidecar and the files it includes,
the CSV laws, certificates) and with its other outputs; a collision is refused by name.

Commands name their files through the options below (argparse destinations); a command that writes a file
no option names (the Extended-URDF export's .yaml sidecar) declares it with `set_defaults(also_writes=fn)`,
fn(args) -> {what: path}. Standard output (`-`) collides with nothing.
"""

from __future__ import annotations

import argparse
import os
from collections.abc import Callable
from pathlib import Path

from mechkit.base.atomic import is_stdout
from mechkit.base.exceptions import OutputError

#: Destination -> the option as typed, for every option naming a file (or folder) a command writes.
OUTPUT_OPTIONS = {
    "output": "-o",
    "plot": "--plot",
    "animate": "--animate",
    "png": "--png",
    "markdown": "--markdown",
    "charts": "--charts",
}
#: Destination -> the option as typed, for every option naming a file a command reads.
INPUT_OPTIONS = {
    "inputs": "--inputs",
    "torques": "--torques",
    "base_motion": "--base-motion",
    "tls_ca": "--tls-ca",
    "tls_cert": "--tls-cert",
    "tls_key": "--tls-key",
}


def outputs(args: argparse.Namespace) -> dict[str, str]:
    """What the command line asks a command to write.

    Args:
        args: the parsed command line.

    Returns:
        What (the option, or the file a command adds) -> the path as given; standard output left out.
    """
    named = {option: getattr(args, dest, None) for dest, option in OUTPUT_OPTIONS.items()}
    extra: Callable[[argparse.Namespace], dict[str, str]] | None = getattr(args, "also_writes", None)
    if extra is not None:
        named.update(extra(args))
    return {what: str(path) for what, path in named.items() if path and not is_stdout(path)}


def inputs(args: argparse.Namespace) -> dict[Path, str]:
    """The files the command line makes a command read.

    Args:
        args: the parsed command line.

    Returns:
        Resolved file -> what it is to the user (the description, a file it includes, an option's file).
    """
    from mechkit.catalog.registry import get_spec
    from mechkit.catalog.registry import names as registered
    from mechkit.sources.input_files import description_files  # the readers load only for a file given

    found: dict[Path, str] = {}
    names = [getattr(args, "name", None), *(getattr(args, "names", None) or [])]  # `bench` takes several
    for name in (n for n in names if n):
        if Path(name).expanduser().is_file():
            source, first, reader = Path(name), f"the description {name}", name
        elif name in registered():  # its xacro template (and the macros it includes) is read too
            source = get_spec(name).template_path
            first, reader = f"the xacro template of {name}", source.name
        else:
            continue
        for k, path in enumerate(description_files(source)):
            found.setdefault(path, first if k == 0 else f"{path.name}, which {reader} reads")
    for dest, option in INPUT_OPTIONS.items():
        value = getattr(args, dest, None)
        if value:
            found.setdefault(_resolved(value), f"the {option} file {value}")
    return found


def check(args: argparse.Namespace) -> None:
    """Refuse, before any work, an output that is an input of the command or another of its outputs.

    Args:
        args: the parsed command line.

    Raises:
        OutputError: naming the option, the file and what it would destroy.
    """
    read = inputs(args)
    written: dict[Path, str] = {}
    for what, path in outputs(args).items():
        target = _resolved(path)
        if target in read:
            raise OutputError(path, f"{what} would overwrite {read[target]}: choose another file")
        if target in written:
            raise OutputError(path, f"{what} and {written[target]} name the same file: choose two")
        written[target] = what


def _resolved(path: str | os.PathLike) -> Path:
    """The file a path names, symlinks followed (a file that does not exist yet resolves as well)."""
    return Path(os.path.realpath(Path(path).expanduser(), strict=False))
