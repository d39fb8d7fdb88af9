"""`mechkit sweep`: the cluster options checked before anything is written (the sweeps themselves:
tests/sweep/test_cluster.py)."""

from __future__ import annotations

import pytest

from mechkit.cli import main


@pytest.mark.parametrize(
    "args, name",
    [
        (("--tls-ca", "ca.pem"), "tls_ca"),  # TLS files without a tls:// scheduler
        (("--scheduler", "tcp://127.0.0.1:1", "--tls-cert", "cert.pem"), "tls_cert"),
        (("--scheduler", "tls://127.0.0.1:1", "--tls-key", "missing.pem"), "tls_key"),
        (("--scheduler", "tls://127.0.0.1:1"), "scheduler"),  # no CA or client certificate anywhere
        (("--scheduler", "tcp://127.0.0.1:1", "--dashboard"), "dashboard"),  # a running scheduler has its own
        (("--wait-workers", "-1"), "wait_workers"),
        (("--wait-workers", "nan"), "wait_workers"),
    ],
)
def test_cluster_options_are_checked_before_anything_is_written(args, name, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("MECHKIT_DASK_SCHEDULER", raising=False)
    for pem in ("ca.pem", "cert.pem"):
        (tmp_path / pem).write_text("not read: the options are refused first\n")
    status = main(["sweep", "four_bar", "--grid", "crank=0.06:0.12:2", "-o", "r", "-q", *args])
    err = capsys.readouterr().err
    assert status == 2 and f"argument {name!r}" in err and "Traceback" not in err, err
    assert not (tmp_path / "r").exists()
