"""The bad-input campaign over the command line, in subprocesses: every refusal is one line on stderr and
exit status 2, no traceback, no file replaced or half-written; a broken pipe ends quietly."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ENV = {**os.environ, "PYTHONPATH": str(Path(__file__).resolve().parent.parent)}


def run(*args: str, cwd: Path | None = None) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "mechkit", *args], capture_output=True, text=True, env=ENV, cwd=cwd,
                          check=False, timeout=300)


def refused(out: subprocess.CompletedProcess, *words: str) -> None:
    assert out.returncode == 2, out.stderr
    assert "Traceback" not in out.stderr and out.stderr.startswith("mechkit: error: ")
    assert len(out.stderr.strip().splitlines()) == 1, out.stderr
    for word in words:
        assert word in out.stderr, out.stderr


def test_device_fifo_directory_and_file_parent_are_refused(tmp_path):
    fifo = tmp_path / "f"
    os.mkfifo(fifo)
    (tmp_path / "file").write_text("x")
    for target, word in (("/dev/null", "device"), (str(fifo), "FIFO"), (str(tmp_path), "directory"),
                         (str(tmp_path / "file" / "a.urdf"), "not a directory")):
        refused(run("urdf", "five_bar", "-o", target), word)
    assert fifo.is_fifo() and (tmp_path / "file").read_text() == "x"


def test_symlink_is_written_through_and_dash_is_stdout(tmp_path):
    real = tmp_path / "real.urdf"
    real.write_text("old")
    (tmp_path / "link.urdf").symlink_to(real)
    out = run("urdf", "five_bar", "-o", str(tmp_path / "link.urdf"))
    assert out.returncode == 0 and (tmp_path / "link.urdf").is_symlink()
    assert real.read_text().startswith("<?xml")
    dash = run("urdf", "five_bar", "-o", "-")
    assert dash.returncode == 0 and dash.stdout == real.read_text()


def test_extended_urdf_sidecar_cannot_overwrite_the_urdf(tmp_path):
    target = tmp_path / "z.yaml"
    target.write_text("keep")
    refused(run("export", "five_bar", "--format", "extended-urdf", "-o", str(target)), "sidecar")
    assert target.read_text() == "keep" and sorted(p.name for p in tmp_path.iterdir()) == ["z.yaml"]
    out = run("export", "five_bar", "--format", "extended-urdf", "-o", str(tmp_path / "z.urdf"))
    assert out.returncode == 0 and (tmp_path / "z.urdf").exists() and (tmp_path / "z.yaml").read_text() != "keep"


def test_broken_pipe_ends_quietly():
    proc = subprocess.Popen(f"{sys.executable} -m mechkit urdf deployable_9rr12uru | head -c 10", shell=True,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=ENV)
    out, err = proc.communicate(timeout=300)
    assert out == b"<?xml vers" and b"Traceback" not in err and err == b""


@pytest.mark.parametrize("args,words", [
    (("bench", "nope", "--quick"), ("nope",)),
    (("urdf", "nope"), ("nope",)),
    (("urdf", "five_bar", "--set", "bogus=1"), ("bogus",)),
    (("urdf", "five_bar", "--set", "prox1=nan"), ("prox1",)),
    (("urdf", "five_bar", "--set", "prox1=-1"), ("prox1",)),
    (("urdf", "five_bar", "--set", "density=1e-12"), ("mass",)),
    (("urdf", "five_bar", "--set", "prox1"), ("name=value",)),
    (("report", "tetra_3rr3uru", "--set", "gamma_ref=0.0623"), ("fold: node positions",)),
    (("report", "five_bar", "--set", "rows=spherical"), ("kkt_vs_proximal",)),
    (("report", "ten_bar", "--set", "deploy_time=1e-300"), ("numerical failure",)),
    (("bench", "--quick", "--markdown", "/dev/null", "four_bar"), ("device",)),
])
def test_named_refusals(args, words):
    refused(run(*args), *words)
