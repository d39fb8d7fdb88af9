"""Progress bars (tqdm) of the long commands: drawn only when asked, one bar per label, closed at the end."""

from __future__ import annotations

import re
from importlib.metadata import version

import pytest
from tests_support import ROOT

from mechkit.cli.progress import ProgressBars, wanted


def test_bars_only_when_asked(capsys):
    bars = ProgressBars(enabled=False)
    bars("x", 1, 2, "a")
    bars("x", 2, 2, "b")
    assert capsys.readouterr().err == ""


def test_one_bar_per_label_advanced_and_closed(capsys):
    bars = ProgressBars(enabled=True)
    bars("four_bar", 1, 3, "kkt")
    bars("five_bar", 1, 2, "newton")
    assert set(bars._bars) == {"four_bar", "five_bar"}
    bars("four_bar", 3, 3, "mujoco")
    bars("five_bar", 2, 2, "lm")
    assert bars._bars == {}
    err = capsys.readouterr().err
    assert re.search(r"four_bar: 100%.*3/3.*mujoco", err) and re.search(r"five_bar: 100%.*2/2.*lm", err)


def test_environment_turns_bars_on(monkeypatch):
    monkeypatch.setenv("MECHKIT_PROGRESS", "1")
    assert wanted()
    monkeypatch.setenv("MECHKIT_PROGRESS", "0")
    assert ProgressBars().enabled == wanted()


def test_installed_tqdm_is_within_the_pin():
    """The tqdm the tests run with satisfies pyproject's pin (its lower bound is the tested version)."""
    tomllib = pytest.importorskip("tomllib")  # Python >= 3.11
    deps = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["dependencies"]
    pin = next(d for d in deps if d.startswith("tqdm"))
    low, high = re.fullmatch(r"tqdm>=([\d.]+),<([\d.]+)", pin).groups()
    installed = tuple(int(x) for x in version("tqdm").split(".")[:3])
    assert tuple(int(x) for x in low.split(".")) <= installed < tuple(int(x) for x in high.split("."))
