"""The elastic tests (a package: tests/core has its own test_model.py)."""
