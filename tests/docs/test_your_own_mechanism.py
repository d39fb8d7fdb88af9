"""docs/your_own_mechanism.md runs as written: every `mechkit` command and every Python block, in a scratch
folder holding the fixtures; the outputs shown must be what they print (self-check values, which are
rounding noise, must stay below 1e-9 instead)."""

from __future__ import annotations

import contextlib
import io
import re
import shutil
from pathlib import Path

import pytest
from tests_support import ROOT

from mechkit.cli import main

PAGE = (ROOT / "docs" / "your_own_mechanism.md").read_text()
CHECK_LINE = re.compile(r"^    (\w+)\s+([-+0-9.e]+)$")


def _blocks(kind: str) -> list[str]:
    return re.findall(rf"```{kind}\n(.*?)```\n", PAGE, flags=re.DOTALL)


def _commands() -> list[tuple[str, list[str]]]:
    out = []
    for block in _blocks("console"):
        for chunk in block.split("$ ")[1:]:
            command, *shown = chunk.rstrip("\n").split("\n")
            out.append((command, shown))
    return out


@pytest.fixture(scope="module")
def scratch(tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("page")
    shutil.copytree(ROOT / "tests" / "fixtures", folder / "tests" / "fixtures")
    return folder


def test_the_page_shows_each_format_and_command():
    commands = " ".join(c for c, _ in _commands())
    for word in (
        "report",
        "urdf",
        "snapshot",
        "export",
        "slider_crank.urdf",
        "watt_six_bar.urdf.xacro",
        "rssr.xml",
        "urdf+",
        "four_bar_gearbox.sdf",
        "2f85.xml",
    ):
        assert word in commands
    assert len(_blocks("python")) == 4


def test_every_command_prints_what_the_page_shows(scratch, monkeypatch, capsys):
    """In process (`mechkit.cli.main`, what `python -m mechkit` runs), in the scratch folder."""
    monkeypatch.chdir(scratch)
    for command, shown in _commands():  # in page order: later commands read what earlier ones wrote
        assert command.startswith("mechkit ")
        assert main(command.split()[1:]) == 0, (command, capsys.readouterr().err)
        stdout = capsys.readouterr().out
        printed = stdout.rstrip("\n").split("\n") if stdout.strip() else []
        assert len(printed) == len(shown), (command, printed)
        for got, expected in zip(printed, shown):
            check = CHECK_LINE.match(expected)
            if check:
                name, value = CHECK_LINE.match(got).groups()
                assert name == check.group(1) and float(value) < 1e-9, (command, got)
            else:
                assert got == expected, command


def test_every_python_block_prints_what_the_page_shows(scratch, monkeypatch):
    monkeypatch.chdir(scratch)
    for code, expected in zip(_blocks("python"), _blocks("text"), strict=True):
        printed = io.StringIO()
        with contextlib.redirect_stdout(printed):
            exec(compile(code, "docs/your_own_mechanism.md", "exec"), {})  # noqa: S102 - the page is ours
        assert printed.getvalue() == expected
