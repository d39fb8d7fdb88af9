"""Broken files in the field's style through the command line: each reader's malformed cases (in its own test
module, each run through `mechkit report`) number at least 30 together."""

from __future__ import annotations

from . import test_extended_urdf, test_mjcf, test_sdf, test_urdf_plus


def test_the_readers_refuse_at_least_30_broken_files_through_the_command_line():
    counts = {
        module.__name__: len(module.MALFORMED) for module in (test_extended_urdf, test_mjcf, test_sdf, test_urdf_plus)
    }
    assert sum(counts.values()) >= 30 and min(counts.values()) >= 10, counts
