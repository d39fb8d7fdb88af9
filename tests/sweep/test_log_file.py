"""`mechkit.sweep.log_file`: during a sweep, distributed's records, Python's warnings and the traceback of
what stopped it go to the log file; the loggers and the warnings are as before afterwards."""

from __future__ import annotations

import logging
import warnings

import pytest

from mechkit.sweep.log_file import LOG, log_to


def test_records_warnings_and_the_stopping_error_go_to_the_file(tmp_path, capsys):
    distributed = logging.getLogger("distributed.scheduler")
    before = (logging.getLogger("distributed").handlers[:], warnings.showwarning)
    with pytest.raises(RuntimeError, match="scheduler gone"), log_to(tmp_path / LOG) as path:
        distributed.warning("worker %s left", "tcp://127.0.0.1:1")
        warnings.warn("dashboard port taken", UserWarning, stacklevel=1)
        raise RuntimeError("scheduler gone")
    text = path.read_text()
    assert "worker tcp://127.0.0.1:1 left" in text
    assert "UserWarning: dashboard port taken" in text
    assert "the sweep stopped" in text and "Traceback" in text and "RuntimeError: scheduler gone" in text
    assert capsys.readouterr().err == ""  # nothing reached the terminal
    assert (logging.getLogger("distributed").handlers[:], warnings.showwarning) == before


def test_a_quiet_sweep_leaves_no_file(tmp_path):
    with log_to(tmp_path / LOG) as path:
        logging.getLogger("an.unrelated.logger").warning("not ours")
    assert not path.exists()  # the handler opens the file on its first record only
