"""Atomic writes: links written through, devices and FIFOs refused, unique synced temporaries, no leftovers."""

from __future__ import annotations

import errno
import os
import threading
from pathlib import Path

import pytest

from mechkit.base import atomic
from mechkit.base.exceptions import OutputError


def _leftovers(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir() if p.name.endswith(".tmp"))


def test_write_replaces_content_and_keeps_mode(tmp_path):
    target = tmp_path / "a.txt"
    target.write_text("old")
    target.chmod(0o640)
    atomic.write_text(target, "new")
    assert target.read_text() == "new"
    assert oct(target.stat().st_mode & 0o777) == oct(0o640)
    assert _leftovers(tmp_path) == []


def test_symlink_is_written_through(tmp_path):
    real = tmp_path / "real.txt"
    real.write_text("old")
    link = tmp_path / "link.txt"
    link.symlink_to(real)
    atomic.write_text(link, "new")
    assert link.is_symlink() and os.readlink(link) == str(real)
    assert real.read_text() == "new"


def test_dangling_symlink_creates_its_target(tmp_path):
    link = tmp_path / "link.txt"
    link.symlink_to(tmp_path / "sub" / "made.txt")
    atomic.write_text(link, "x")
    assert link.is_symlink() and (tmp_path / "sub" / "made.txt").read_text() == "x"


@pytest.mark.parametrize("kind", ["fifo", "device", "directory"])
def test_special_files_are_refused_and_untouched(tmp_path, kind):
    if kind == "fifo":
        path = tmp_path / "f"
        os.mkfifo(path)
    elif kind == "device":
        path = Path("/dev/null")
    else:
        path = tmp_path
    before = os.stat(path)
    with pytest.raises(OutputError, match="FIFO|device|directory"):
        atomic.write_text(path, "x")
    after = os.stat(path)
    assert (before.st_mode, before.st_ino) == (after.st_mode, after.st_ino)
    assert _leftovers(tmp_path) == []


def test_symlink_to_a_device_is_refused(tmp_path):
    link = tmp_path / "null"
    link.symlink_to("/dev/null")
    with pytest.raises(OutputError, match="device"):
        atomic.write_text(link, "x")
    assert link.is_symlink()


def test_stdout_dash(capsys):
    assert atomic.write_text("-", "hello") == Path("-")
    assert capsys.readouterr().out == "hello"


def test_same_file_twice_is_refused(tmp_path):
    a = tmp_path / "a.txt"
    a.write_text("keep")
    (tmp_path / "b.txt").symlink_to(a)
    os.link(a, tmp_path / "c.txt")
    for other in ("./a.txt", "b.txt", "c.txt", "sub/../a.txt"):
        with pytest.raises(OutputError, match="same file"):
            atomic.write_files({str(a): b"1", f"{tmp_path}/{other}": b"2"})
    assert a.read_text() == "keep"
    with pytest.raises(OutputError, match="one output"):
        atomic.write_files({"-": b"1", tmp_path / "d": b"2"})


@pytest.mark.parametrize("failing", ["write", "fsync", "replace"])
def test_failure_leaves_targets_and_no_temporary(tmp_path, monkeypatch, failing):
    a, b = tmp_path / "a.txt", tmp_path / "b.txt"
    a.write_text("A")
    b.write_text("B")
    calls = {"n": 0}

    def boom(*args, **kwargs):
        raise OSError(errno.ENOSPC, "No space left on device")

    if failing == "write":
        real = atomic._write_temp

        def second_fails(target, data):
            calls["n"] += 1
            if calls["n"] == 2:
                boom()
            return real(target, data)

        monkeypatch.setattr(atomic, "_write_temp", second_fails)
    else:
        monkeypatch.setattr(atomic.os, failing, boom)
    with pytest.raises(OutputError, match="No space left"):
        atomic.write_files({a: b"new a", b: b"new b"})
    assert (a.read_text(), b.read_text()) == ("A", "B")
    assert _leftovers(tmp_path) == []


def test_data_is_synced_before_the_rename(tmp_path, monkeypatch):
    events = []
    real_fsync, real_replace = os.fsync, os.replace
    monkeypatch.setattr(atomic.os, "fsync", lambda fd: (events.append("fsync"), real_fsync(fd))[1])
    monkeypatch.setattr(atomic.os, "replace", lambda s, d: (events.append("replace"), real_replace(s, d))[1])
    atomic.write_text(tmp_path / "x", "data")
    assert events.index("fsync") < events.index("replace")


def test_parent_that_is_a_file_is_refused(tmp_path):
    (tmp_path / "file").write_text("x")
    with pytest.raises(OutputError, match="not a directory"):
        atomic.write_text(tmp_path / "file" / "out.txt", "y")


def test_concurrent_writers_to_one_name_do_not_collide(tmp_path):
    target = tmp_path / "same.png"
    errors: list[BaseException] = []

    def write(k: int) -> None:
        try:
            for _ in range(20):
                atomic.write_bytes(target, bytes([k]) * 1000)
        except BaseException as err:  # noqa: BLE001 - collected for the assertion
            errors.append(err)

    threads = [threading.Thread(target=write, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert errors == []
    data = target.read_bytes()
    assert len(data) == 1000 and len(set(data)) == 1  # one writer's whole file, never a mix
    assert _leftovers(tmp_path) == []
