"""`mechkit urdf`: the generated file, written whole or not at all, with an ordinary mode; outputs that
are not regular files refused (a device, a FIFO, a directory), links written through, "-" is stdout."""

from __future__ import annotations

import os

from tests_support import refused, run_mechkit

from mechkit.cli import main


def test_urdf_writes_the_generated_file(tmp_path):
    path = tmp_path / "fb.urdf"
    assert main(["urdf", "four_bar", "--set", "crank=0.12", "-o", str(path)]) == 0
    text = path.read_text()
    assert "<mechkit:loop" in text and 'xyz="0.12 0 0"' in text


def test_failed_urdf_writes_nothing(tmp_path):
    path = tmp_path / "bad.urdf"
    assert main(["urdf", "four_bar", "--set", "ground=2", "-o", str(path)]) == 2
    assert not path.exists() and not list(tmp_path.iterdir())


def test_written_files_have_an_ordinary_mode(tmp_path):
    import os
    import stat

    path = tmp_path / "fb.urdf"
    assert main(["urdf", "four_bar", "-o", str(path)]) == 0
    umask = os.umask(0)
    os.umask(umask)
    assert stat.S_IMODE(path.stat().st_mode) == 0o666 & ~umask


def test_device_fifo_directory_and_file_parent_are_refused(tmp_path):
    fifo = tmp_path / "f"
    os.mkfifo(fifo)
    (tmp_path / "file").write_text("x")
    for target, word in (
        ("/dev/null", "device"),
        (str(fifo), "FIFO"),
        (str(tmp_path), "directory"),
        (str(tmp_path / "file" / "a.urdf"), "not a directory"),
    ):
        refused(run_mechkit("urdf", "five_bar", "-o", target), word)
    assert fifo.is_fifo() and (tmp_path / "file").read_text() == "x"


def test_symlink_is_written_through_and_dash_is_stdout(tmp_path):
    real = tmp_path / "real.urdf"
    real.write_text("old")
    (tmp_path / "link.urdf").symlink_to(real)
    out = run_mechkit("urdf", "five_bar", "-o", str(tmp_path / "link.urdf"))
    assert out.returncode == 0 and (tmp_path / "link.urdf").is_symlink()
    assert real.read_text().startswith("<?xml")
    dash = run_mechkit("urdf", "five_bar", "-o", "-")
    assert dash.returncode == 0 and dash.stdout == real.read_text()
