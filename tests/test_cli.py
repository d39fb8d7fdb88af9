"""`mechkit.cli`: the parser (every command's help ends with two examples that parse) and `main`: a
refusal is one line on stderr and exit status 2, no traceback; a broken pipe ends quietly."""

from __future__ import annotations

import json
import os
import re
import shlex
import subprocess
import sys

import pinocchio as pin
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from tests_support import ROOT, refused, run_mechkit

from mechkit.catalog.registry import ENTRIES
from mechkit.cli import COMMANDS, build_parser, main


def _subparsers() -> dict[str, object]:
    parser = build_parser()
    action = next(a for a in parser._actions if a.dest == "command")
    return dict(action.choices)


def test_every_command_ends_its_help_with_two_examples_that_parse():
    subs = _subparsers()
    assert len(subs) == len(COMMANDS)
    for name, sub in subs.items():
        lines = sub.format_help().rstrip().splitlines()
        assert lines[-3] == "examples:", (
            f"`mechkit {name} --help` must end with two examples: pass "
            f"**mechkit.cli.common.examples(cmd1, cmd2) to its sub.add_parser"
        )
        for line in lines[-2:]:
            argv = shlex.split(line.split("|")[0])
            assert argv[:2] == ["mechkit", name], line
            args = build_parser().parse_args(argv[1:])  # exits (SystemExit) on a bad example
            assert args.command == name


@pytest.mark.parametrize(
    "args, needle",
    [
        (["report", "four_bar", "--set", "crank=-1"], "'crank'"),
        (["report", "four_bar", "--set", "wheels=3"], "'wheels'"),
        (["report", "four_bar", "--set", "crank"], "expected NAME=VALUE"),
        (["report", "nine_bar"], "no such mechanism"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(args, needle):
    refused(run_mechkit(*args), needle)


def test_broken_pipe_ends_quietly():
    proc = subprocess.Popen(
        f"{sys.executable} -m mechkit urdf deployable_9rr12uru | head -c 10",
        shell=True,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env={**os.environ, "PYTHONPATH": str(ROOT)},
    )
    out, err = proc.communicate(timeout=300)
    assert out == b"<?xml vers" and b"Traceback" not in err and err == b""


@pytest.mark.parametrize(
    "args,words",
    [
        (("bench", "nope", "--quick"), ("nope",)),
        (("urdf", "nope"), ("nope",)),
        (("urdf", "five_bar", "--set", "bogus=1"), ("bogus",)),
        (("urdf", "five_bar", "--set", "prox1=nan"), ("prox1",)),
        (("urdf", "five_bar", "--set", "prox1=-1"), ("prox1",)),
        (("urdf", "five_bar", "--set", "density=1e-12"), ("mass",)),
        (("urdf", "five_bar", "--set", "prox1"), ("--set", "expected NAME=VALUE")),
        (("report", "tetra_3rr3uru", "--set", "gamma_ref=0.0623"), ("fold: node positions",)),
        (("report", "five_bar", "--set", "rows=spherical"), ("kkt_vs_proximal",)),
        (("report", "ten_bar", "--set", "deploy_time=1e-300"), ("numerical failure",)),
        (("bench", "--quick", "--markdown", "/dev/null", "four_bar"), ("device",)),
    ],
)
def test_named_refusals(args, words):
    refused(run_mechkit(*args), *words)


def _strict_json(text: str):
    def refuse(constant):
        raise ValueError(f"{constant} is not JSON")

    return json.loads(text, parse_constant=refuse)


def _heaviest_link(mech) -> str:
    """The URDF link of the mechanism's heaviest moving body."""
    model = mech.model
    body = max(range(1, model.njoints), key=lambda j: model.inertias[j].mass)
    return next(f.name for f in model.frames if f.type == pin.FrameType.BODY and f.parentJoint == body)


@pytest.mark.parametrize("name", [e.name for e in ENTRIES])
def test_every_json_output_is_strict_json_without_non_finite_numbers(name, load_cached, capsys):
    """report, params, validate, modes and stiffness --json of every registered mechanism parse with a parser
    that refuses Infinity and NaN (a stiffness used to print Infinity)."""
    commands = [["report", name, "--json"], ["params", name, "--json"], ["validate", name, "--samples", "2", "--json"]]
    if name != "rocket_gimbal":  # nothing elastic there: refused in one line (tests/elastic)
        commands += [
            ["modes", name, "-n", "2", "--json"],
            ["stiffness", name, "--body", _heaviest_link(load_cached(name)), "--json"],
        ]
    for command in commands:
        code = main(command)
        out = capsys.readouterr().out
        assert code == 0, command
        _strict_json(out)


#: (command line on the four-bar, option taking a drawn value) of the cheap commands.
OPTION_CASES = [
    (["report", "four_bar"], "--set", "ground={}"),
    (["report", "four_bar"], "--lock", "crank={}"),
    (["report", "four_bar"], "--actuated", "{}"),
    (["report", "four_bar"], "--keep", "{}"),
    (["report", "four_bar"], "--fix", "{}"),
    (["urdf", "four_bar", "-o", "-"], "--set", "coupler={}"),
    (["stiffness", "four_bar", "--body", "coupler_link"], "--at", "crank={}"),
    (["stiffness", "four_bar", "--body", "coupler_link"], "--point", "{}"),
    (["modes", "four_bar", "-n", "2"], "--at", "crank={}"),
    (["simulate", "four_bar", "--duration", "0.01"], "--friction", "{}"),
    (["simulate", "four_bar", "--duration", "0.01"], "--gravity", "{}"),
    (["simulate", "four_bar", "--duration", "0.01"], "--spring", "crank={}"),
    (["simulate", "four_bar", "--duration", "0.01"], "--latch", "crank={}"),
    (["snapshot", "four_bar", "-o", "-"], "--q", "{}"),
]
TOKENS = ["nan", "inf", "-inf", "1e300", "-1e300", "abc", "", ",", "1,2", "1,,2", "=", "crank", "0", "-1", "1e-300"]


@settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(case=st.sampled_from(OPTION_CASES), token=st.sampled_from(TOKENS))
def test_a_malformed_option_value_is_one_line_or_a_finite_answer(capsys, case, token):
    """The campaign on option values: every drawn value gives exit 0 with no nan or inf printed, or exit 2 with one
    line naming what is wrong; never an exception out of `main` (a traceback)."""
    command, option, form = case
    code = main([*command, f"{option}={form.format(token)}"])
    out, err = capsys.readouterr()
    assert code in (0, 2), (case, token, code, err)
    if code == 2:
        assert err.startswith("mechkit: error: ") and err.count("\n") == 1, (case, token, err)
    else:
        assert not re.search(r"\b(nan|inf|infinity)\b", out, re.IGNORECASE), (case, token, out[-500:])
