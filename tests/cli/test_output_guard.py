"""`mechkit.cli.output_guard`: for every command and every option naming a file it writes, an output that is
one of the command's inputs (the description, its sidecar, a file it includes, a law or torques CSV) or
another of its outputs is refused in one line, exit 2, before any work, the input byte for byte as it was."""

from __future__ import annotations

import os
import shutil

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from tests_support import FIXTURES, ROOT, refused, run_mechkit

from mechkit import cli
from mechkit.cli import main, output_guard

FOUR_BAR = ROOT / "urdf" / "four_bar.urdf"
LAW = "t,crank\n0,0.5\n0.1,0.6\n"
TORQUES = "t,crank\n0,0.0\n0.1,0.0\n"


@pytest.fixture
def files(tmp_path):
    """A folder with a description (four_bar.urdf), an Extended URDF with its sidecar (leg.urdf, leg.yaml),
    a xacro including another (top.urdf.xacro, macros.xacro), a law and a torques CSV."""
    shutil.copy(FOUR_BAR, tmp_path / "four_bar.urdf")
    shutil.copy(FIXTURES / "leg.urdf", tmp_path / "leg.urdf")
    shutil.copy(FIXTURES / "leg.yaml", tmp_path / "leg.yaml")
    shutil.copy(ROOT / "xacro" / "four_bar.urdf.xacro", tmp_path / "top.urdf.xacro")
    shutil.copy(ROOT / "xacro" / "macros.xacro", tmp_path / "macros.xacro")
    (tmp_path / "law.csv").write_text(LAW)
    (tmp_path / "torques.csv").write_text(TORQUES)
    return tmp_path


#: (command line with {d} for the folder, the input it names as an output, the option, what is named).
CASES = [
    ("urdf {d}/four_bar.urdf -o {d}/four_bar.urdf", "four_bar.urdf", "-o", "the description"),
    ("urdf {d}/leg.urdf -o {d}/leg.yaml", "leg.yaml", "-o", "leg.yaml, which"),
    ("urdf {d}/top.urdf.xacro -o {d}/macros.xacro", "macros.xacro", "-o", "macros.xacro, which"),
    ("snapshot {d}/four_bar.urdf -o {d}/four_bar.urdf", "four_bar.urdf", "-o", "the description"),
    ("snapshot {d}/four_bar.urdf --png {d}/four_bar.urdf", "four_bar.urdf", "--png", "the description"),
    ("export {d}/four_bar.urdf --format mjcf -o {d}/four_bar.urdf", "four_bar.urdf", "-o", "the description"),
    ("export {d}/four_bar.urdf --format extended-urdf -o {d}/four_bar.yaml", "four_bar.urdf", "-o", "sidecar"),
    ("motion {d}/four_bar.urdf --inputs {d}/law.csv -o {d}/law.csv", "law.csv", "-o", "the --inputs file"),
    ("motion four_bar --inputs {d}/law.csv --plot {d}/law.csv", "law.csv", "--plot", "the --inputs file"),
    ("simulate {d}/four_bar.urdf --duration 0.1 -o {d}/four_bar.urdf", "four_bar.urdf", "-o", "the description"),
    (
        "simulate four_bar --duration 0.1 --torques {d}/torques.csv --plot {d}/torques.csv",
        "torques.csv",
        "--plot",
        "--torques",
    ),
    ("simulate four_bar --duration 0.1 --inputs {d}/law.csv --animate {d}/law.csv", "law.csv", "--animate", "--inputs"),
    (
        "motion spherical_2dof --base moving --base-motion {d}/law.csv --hold platform -o {d}/law.csv",
        "law.csv",
        "-o",
        "the --base-motion file",
    ),
    ("modes {d}/four_bar.urdf --animate {d}/four_bar.urdf", "four_bar.urdf", "--animate", "the description"),
    ("sweep {d}/four_bar.urdf --grid crank=0.09:0.11:2 -o {d}/four_bar.urdf", "four_bar.urdf", "-o", "the description"),
    ("bench {d}/four_bar.urdf --quick --markdown {d}/four_bar.urdf", "four_bar.urdf", "--markdown", "the description"),
    ("bench {d}/four_bar.urdf --quick --charts {d}/four_bar.urdf", "four_bar.urdf", "--charts", "the description"),
]


def _command(line: str, folder) -> list[str]:
    return line.format(d=folder).split()


@pytest.mark.parametrize("line, victim, option, named", CASES, ids=[c[0].split()[0] + " " + c[2] for c in CASES])
def test_an_output_that_is_an_input_is_refused_before_any_work(files, monkeypatch, capsys, line, victim, option, named):
    """The command's own work (its `run`) never starts; the input keeps its bytes and its time stamp."""
    args = _command(line, files)
    module = getattr(cli, args[0])

    def never(_args):
        raise AssertionError("the command started its work")

    monkeypatch.setattr(module, "run", never)
    before = (files / victim).read_bytes(), os.stat(files / victim).st_mtime_ns
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.startswith("mechkit: error: ") and err.count("\n") == 1, err
    assert option in err and named in err, err
    assert ((files / victim).read_bytes(), os.stat(files / victim).st_mtime_ns) == before


def test_every_output_option_of_every_command_is_covered():
    """A command that gains an option writing a file (a destination in `OUTPUT_OPTIONS`) must appear in
    `CASES` with that option: the guard's coverage cannot fall behind the commands."""
    parser = cli.build_parser()
    commands = next(a for a in parser._actions if a.dest == "command").choices
    covered = {(c[0].split()[0], c[2]) for c in CASES}
    for name, sub in commands.items():
        for action in sub._actions:
            if action.dest in output_guard.OUTPUT_OPTIONS:
                assert (name, output_guard.OUTPUT_OPTIONS[action.dest]) in covered, (name, action.dest)


def test_two_outputs_naming_one_file_are_refused(files, capsys):
    assert (
        main(["simulate", "four_bar", "--duration", "0.1", "-o", str(files / "a.csv"), "--plot", str(files / "a.csv")])
        == 2
    )
    err = capsys.readouterr().err
    assert "--plot and -o name the same file" in err and not (files / "a.csv").exists()


def test_a_link_to_an_input_is_the_input(files, capsys):
    """An output given as a symbolic link to the description resolves to it."""
    (files / "link.urdf").symlink_to(files / "four_bar.urdf")
    before = (files / "four_bar.urdf").read_bytes()
    assert main(["urdf", str(files / "four_bar.urdf"), "-o", str(files / "link.urdf")]) == 2
    assert "the description" in capsys.readouterr().err and (files / "four_bar.urdf").read_bytes() == before


def test_standard_output_and_distinct_files_pass(files):
    assert main(["urdf", str(files / "four_bar.urdf"), "-o", "-"]) == 0
    assert main(["urdf", str(files / "four_bar.urdf"), "-o", str(files / "copy.urdf")]) == 0
    assert (files / "copy.urdf").read_text().startswith("<?xml")


def test_the_command_line_refuses_in_one_line_with_exit_2(files):
    """End to end, in a subprocess: the user's file survives `mechkit urdf F -o F`."""
    before = (files / "four_bar.urdf").read_bytes()
    out = run_mechkit("urdf", str(files / "four_bar.urdf"), "-o", str(files / "four_bar.urdf"))
    refused(out, "-o would overwrite the description")
    assert (files / "four_bar.urdf").read_bytes() == before


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    case=st.sampled_from([c for c in CASES if f"{c[2]} {{d}}/{c[1]}" in c[0]]),  # the output names the input
    spelling=st.sampled_from(["plain", "dot", "parent", "double_slash", "link", "absolute_via_link_dir"]),
)
def test_any_spelling_of_an_input_is_still_the_input(files, monkeypatch, capsys, case, spelling):
    """The same collisions, the output spelt otherwise: ./x, a detour through a folder and .., a doubled slash, a
    link to the file, a path through a linked folder. Refused every time, the input untouched."""
    line, victim, option, named = case
    target = files / victim
    spelt = {
        "plain": str(target),
        "dot": f"{files}/./{victim}",
        "parent": f"{files}/sub/../{victim}",
        "double_slash": f"{files}//{victim}",
        "link": str(files / f"link_to_{victim}"),
        "absolute_via_link_dir": str(files / "linked_dir" / victim),
    }[spelling]
    (files / "sub").mkdir(exist_ok=True)
    if not (files / f"link_to_{victim}").exists():
        (files / f"link_to_{victim}").symlink_to(target)
    if not (files / "linked_dir").exists():
        (files / "linked_dir").symlink_to(files)
    args = _command(line, files)
    position = next(k for k, a in enumerate(args) if a == str(target) and args[k - 1] == option)
    args[position] = spelt
    monkeypatch.setattr(getattr(cli, args[0]), "run", lambda _args: pytest.fail("the command started its work"))
    before = target.read_bytes(), os.stat(target).st_mtime_ns
    assert main(args) == 2
    err = capsys.readouterr().err
    assert option in err and named in err, (spelling, err)
    assert (target.read_bytes(), os.stat(target).st_mtime_ns) == before


@pytest.mark.parametrize("file", ["four_bar.urdf.xacro", "macros.xacro"])
def test_a_registered_mechanisms_template_is_an_input(file, tmp_path, monkeypatch, capsys):
    """`mechkit urdf four_bar -o <the repository's template>` (here through a link, as it goes unnoticed)
    wrote over the template: a registered name reads its xacro template and the macros it includes."""
    template = ROOT / "xacro" / file
    (tmp_path / "out.urdf").symlink_to(template)
    monkeypatch.setattr(cli.urdf, "run", lambda _args: pytest.fail("the command started its work"))
    before = template.read_bytes(), os.stat(template).st_mtime_ns
    assert main(["urdf", "four_bar", "-o", str(tmp_path / "out.urdf")]) == 2
    err = capsys.readouterr().err
    named = (
        "the xacro template of four_bar"
        if file == "four_bar.urdf.xacro"
        else f"{file}, which four_bar.urdf.xacro reads"
    )
    assert err.startswith("mechkit: error: ") and f"-o would overwrite {named}" in err, err
    assert (template.read_bytes(), os.stat(template).st_mtime_ns) == before
