"""`mechkit sweep`: the cluster options checked before anything is written (the sweeps themselves:
tests/sweep/test_cluster.py)."""

from __future__ import annotations

import pytest

from mechkit.cli import main


@pytest.mark.parametrize(
    "args, option",
    [
        (("--tls-ca", "ca.pem"), "--tls-ca"),  # TLS files without a tls:// scheduler
        (("--scheduler", "tcp://127.0.0.1:1", "--tls-cert", "cert.pem"), "--tls-cert"),
        (("--scheduler", "tls://127.0.0.1:1", "--tls-key", "missing.pem"), "--tls-key"),
        (("--scheduler", "tls://127.0.0.1:1"), "--scheduler"),  # no CA or client certificate anywhere
        (("--scheduler", "tcp://127.0.0.1:1", "--dashboard"), "--dashboard"),  # a running scheduler has its own
        (("--wait-workers", "-1"), "--wait-workers"),
        (("--wait-workers", "nan"), "--wait-workers"),
    ],
)
def test_cluster_options_are_checked_before_anything_is_written(args, option, tmp_path, capsys, monkeypatch):
    """Refused in one line naming the option as typed (the cluster's keyword, `tls_ca`, said as `--tls-ca`)."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("MECHKIT_DASK_SCHEDULER", raising=False)
    for pem in ("ca.pem", "cert.pem"):
        (tmp_path / pem).write_text("not read: the options are refused first\n")
    status = main(["sweep", "four_bar", "--grid", "crank=0.06:0.12:2", "-o", "r", "-q", *args])
    err = capsys.readouterr().err
    assert status == 2 and err.startswith(f"mechkit: error: {option}: ") and "Traceback" not in err, err
    assert not (tmp_path / "r").exists()


@pytest.mark.parametrize("args", [["--maximise"], ["--starts", "3"], ["--evaluations", "10"]])
def test_a_refinement_option_without_optimise_is_refused(args, tmp_path, capsys, monkeypatch):
    """--maximise, --starts and --evaluations tune --optimise: alone they were ignored after a whole sweep."""
    monkeypatch.chdir(tmp_path)
    assert main(["sweep", "four_bar", "--grid", "crank=0.06:0.12:2", "-o", "r", "-q", *args]) == 2
    err = capsys.readouterr().err
    assert (
        err.startswith(f"mechkit: error: argument '{args[0]}': tunes the refinement: give --optimise")
        and err.count("\n") == 1
    )
    assert list(tmp_path.iterdir()) == []
