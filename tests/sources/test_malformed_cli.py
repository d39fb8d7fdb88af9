"""Broken files in the field's style through the command line: each reader's malformed cases (in its own test
module, each run through `mechkit report`) number at least 30 together, and `mechkit validate` of a tree
with no loop (example-robot-data's Panda) is one line, exit 2, no traceback."""

from __future__ import annotations

import contextlib
import io
import sysconfig
from pathlib import Path

import test_extended_urdf
import test_mjcf
import test_sdf
import test_urdf_plus

from mechkit.cli import main

PANDA = Path(sysconfig.get_paths()["purelib"], "cmeel.prefix", "share", "example-robot-data", "robots",
             "panda_description", "urdf", "panda.urdf")


def test_the_readers_refuse_at_least_30_broken_files_through_the_command_line():
    counts = {module.__name__: len(module.MALFORMED) for module in (test_extended_urdf, test_mjcf, test_sdf, test_urdf_plus)}
    assert sum(counts.values()) >= 30 and min(counts.values()) >= 10, counts


def test_validate_of_a_tree_with_no_loop_is_one_line():
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(["validate", str(PANDA)])
    lines = err.getvalue().strip().splitlines()
    assert code == 2 and out.getvalue() == "" and len(lines) == 1 and lines[0].startswith("mechkit: error: panda")
