"""The code passes the linter and is as the formatter writes it, at the pinned version (ruff, configured in
pyproject.toml: line length 120)."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def test_ruff_finds_nothing() -> None:
    ruff = shutil.which("ruff", path=str(Path(sys.executable).parent)) or shutil.which("ruff")
    if ruff is None:
        pytest.skip("ruff not installed (it comes with the test extra)")
    out = subprocess.run(
        [ruff, "check", "--output-format", "concise", "mechkit", "tests", "tools"],
        cwd=ROOT,
        check=False,
        capture_output=True,
        text=True,
    )
    assert out.returncode == 0, out.stdout + out.stderr


def test_ruff_format_changes_nothing() -> None:
    ruff = shutil.which("ruff", path=str(Path(sys.executable).parent)) or shutil.which("ruff")
    if ruff is None:
        pytest.skip("ruff not installed (it comes with the test extra)")
    out = subprocess.run(
        [ruff, "format", "--check", "mechkit", "tests", "tools"], cwd=ROOT, check=False, capture_output=True, text=True
    )
    assert out.returncode == 0, out.stdout + out.stderr
