"""`mechkit.catalog.registry`: the table is sorted and unique, and every mechanism package is in it."""

from __future__ import annotations

from pathlib import Path

import mechkit
from mechkit.catalog.registry import names

PACKAGE = Path(mechkit.__file__).resolve().parent


def test_registry_table_is_sorted_and_unique():
    assert list(names()) == sorted(set(names()))


def test_every_mechanism_package_is_registered():
    packages = {p.parent.name for p in (PACKAGE / "mechanisms").glob("*/__init__.py")}
    declaring = {
        name
        for name in packages
        if "SPEC = MechanismSpec(" in (PACKAGE / "mechanisms" / name / "__init__.py").read_text()
    }
    assert declaring == set(names())
