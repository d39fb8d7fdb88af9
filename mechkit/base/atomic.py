"""Atomic file writes: a uniquely named temporary file in the target folder, synced, then renamed.

Outputs are checked before anything is written: `-` means standard output, a symlink is written
through to its final target (the link stays), a directory, a device or a FIFO is refused, and two
outputs of one command that are the same file are refused. A failure at any point removes the
temporary files and leaves every target as it was; every `OSError` becomes an `OutputError`.
"""

from __future__ import annotations

import os
import stat
import sys
import tempfile
from collections.abc import Mapping
from pathlib import Path

from mechkit.base.exceptions import OutputError

#: The output name that means standard output.
STDOUT = "-"


def is_stdout(path: str | os.PathLike | None) -> bool:
    """True for the output name `-` (standard output).

    Args:
        path: an output name, or None.

    Returns:
        Whether it is `-`.
    """
    return path is not None and os.fspath(path) == STDOUT


def resolve_output(path: str | os.PathLike) -> Path:
    """The regular file a write to `path` replaces: symlinks followed (even dangling ones).

    Args:
        path: the output as given.

    Returns:
        The resolved regular file (it may not exist yet).

    Raises:
        OutputError: empty name, a directory, a device, a FIFO or a socket, or a symlink loop.
    """
    if not os.fspath(path):
        raise OutputError(path, "empty file name")
    try:
        target = Path(os.path.realpath(path, strict=False))
        mode = os.stat(target).st_mode if target.exists() else None
    except OSError as err:
        raise OutputError(path, err.strerror or str(err)) from None
    if mode is not None and not stat.S_ISREG(mode):
        kind = (
            "a directory"
            if stat.S_ISDIR(mode)
            else "a FIFO"
            if stat.S_ISFIFO(mode)
            else "a device"
            if stat.S_ISCHR(mode) or stat.S_ISBLK(mode)
            else "not a regular file"
        )
        raise OutputError(path, f"is {kind}; mechkit writes regular files only (use '-' for standard output)")
    if target.parent.exists() and not target.parent.is_dir():
        raise OutputError(path, f"{target.parent} is not a directory")
    return target


def check_distinct(paths: list[str | os.PathLike]) -> list[Path]:
    """Resolve several outputs of one command; refuse two that are the same file.

    Args:
        paths: the outputs as given.

    Returns:
        Their resolved files, in order.

    Raises:
        OutputError: a path refused by `resolve_output`, or two paths naming one file (after
            symlinks, or hard links of an existing file).
    """
    resolved = [resolve_output(p) for p in paths]
    for i, a in enumerate(resolved):
        for j in range(i):
            b = resolved[j]
            if a == b or (a.exists() and b.exists() and os.path.samefile(a, b)):
                raise OutputError(paths[i], f"is the same file as the other output {os.fspath(paths[j])!r}")
    return resolved


def write_text(path: str | os.PathLike, text: str) -> Path:
    """Write `text` (UTF-8) to `path` atomically, or to standard output when `path` is `-`.

    Args:
        path: the output, or `-`.
        text: the content.

    Returns:
        The path as given (`Path("-")` for standard output).

    Raises:
        OutputError: the output is refused (see `write_files`) or cannot be written.
    """
    if is_stdout(path):
        sys.stdout.write(text)
        sys.stdout.flush()
        return Path(STDOUT)
    return write_files({path: text.encode()})[0]


def write_bytes(path: str | os.PathLike, data: bytes) -> Path:
    """Write `data` to `path` atomically.

    Args:
        path: the output.
        data: the content.

    Returns:
        The path as given.

    Raises:
        OutputError: the output is refused (see `write_files`) or cannot be written.
    """
    return write_files({path: data})[0]


def write_files(contents: Mapping[str | os.PathLike, bytes]) -> list[Path]:
    """Write several files as one step: every temporary file is written and synced before any rename.

    Args:
        contents: output as given -> its bytes.

    Returns:
        The paths as given, in order.

    Raises:
        OutputError: an output refused (see `check_distinct`) or an `OSError` while writing; no
            temporary file is left and no target has changed (a rename failing after another succeeded
            is the one exception: it names the files already replaced).
    """
    paths = list(contents)
    if any(is_stdout(p) for p in paths) and len(paths) > 1:
        raise OutputError(STDOUT, "standard output can take one output only")
    targets = check_distinct(paths)
    temps: list[str] = []
    done: list[Path] = []
    current = paths[0]
    try:
        for path, target in zip(paths, targets):
            current = path
            temps.append(_write_temp(target, contents[path]))
        for path, target, tmp in zip(paths, targets, temps):
            current = path
            os.replace(tmp, target)
            done.append(target)
        if targets:
            _sync_dir(targets[-1].parent)
    except OSError as err:
        replaced = f" (already replaced: {', '.join(map(str, done))})" if done else ""
        raise OutputError(current, f"{err.strerror or err}{replaced}") from None
    finally:
        for tmp in temps:
            if os.path.lexists(tmp):
                os.unlink(tmp)
    return [Path(p) for p in paths]


def _write_temp(target: Path, data: bytes) -> str:
    """A synced temporary file beside `target`, with the target's mode (an ordinary file's when new)."""
    target.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        if target.exists():
            mode = stat.S_IMODE(os.stat(target).st_mode)
        else:
            umask = os.umask(0)
            os.umask(umask)
            mode = 0o666 & ~umask  # mkstemp makes it owner-only; give it an ordinary file's mode
        os.chmod(tmp, mode)
    except BaseException:
        os.unlink(tmp)
        raise
    return tmp


def _sync_dir(folder: Path) -> None:
    """Sync a folder so the renames in it survive a crash (best effort where folders cannot be opened)."""
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)
