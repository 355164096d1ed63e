"""Shared set-up of the Python suite. ctest runs each test_*.py with PYTHONPATH=<build>/python and
TIRPOL_SOURCE_DIR set; a missing numpy, pytest or built package makes the tests fail, never skip."""

import os
import pathlib

import numpy  # noqa: F401  (import error = test failure: the package needs numpy)
import pytest


@pytest.fixture(scope="session")
def source_dir() -> pathlib.Path:
    value = os.environ.get("TIRPOL_SOURCE_DIR")
    assert value, "TIRPOL_SOURCE_DIR is not set (ctest sets it; see tests/python/README in docs/python.md)"
    return pathlib.Path(value)


@pytest.fixture()
def cache_dir(tmp_path) -> pathlib.Path:
    """A private emissivity-table cache so that tests never share disk state."""
    return tmp_path / "emissivity-cache"
