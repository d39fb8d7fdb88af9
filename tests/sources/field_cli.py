"""`mechkit report` on a file, as a user runs it (the command line's `main`, in this process): its JSON
report, or its one-line refusal. A traceback is an exception out of `main`, which fails the test."""

from __future__ import annotations

import contextlib
import io
import json
from pathlib import Path
from typing import Any

from mechkit.cli import main


def _run(path: Path, options: tuple[str, ...]) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(["report", "--json", str(path), *options])
    return code, out.getvalue(), err.getvalue()


def report(path: Path, *options: str) -> dict[str, Any]:
    """The JSON report of `mechkit report --json PATH OPTIONS...`, which must exit 0 and print nothing on stderr."""
    code, out, err = _run(path, options)
    assert code == 0 and not err, err
    return json.loads(out)


def refusal(path: Path, *options: str) -> str:
    """The one line `mechkit report PATH OPTIONS...` prints on stderr when it refuses (exit 2, no report)."""
    code, out, err = _run(path, options)
    lines = err.strip().splitlines()
    assert code == 2 and not out and len(lines) == 1 and lines[0].startswith("mechkit: error: "), (code, err)
    return lines[0]
