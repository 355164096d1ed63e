"""Shared set-up of the Python suite. ctest runs each test_*.py with PYTHONPATH=<build>/python and
TIRPOL_SOURCE_DIR set; a missing numpy, pytest or built package makes the tests fail, never skip."""

import fcntl
import os
import pathlib
import shutil
import subprocess
import time

import numpy  # noqa: F401  (import error = test failure: the package needs numpy)
import pytest

import tirpol
from tirpol import acquisition

FAKE_GIGE = "arv-fake-gv-camera-0.8"


@pytest.fixture(scope="session")
def source_dir() -> pathlib.Path:
    value = os.environ.get("TIRPOL_SOURCE_DIR")
    assert value, "TIRPOL_SOURCE_DIR is not set (ctest sets it; see tests/python/README in docs/python.md)"
    return pathlib.Path(value)


@pytest.fixture()
def cache_dir(tmp_path) -> pathlib.Path:
    """A private emissivity-table cache so that tests never share disk state."""
    return tmp_path / "emissivity-cache"


@pytest.fixture()
def fake_gige_camera():
    """Aravis's own fake GigE Vision camera (`arv-fake-gv-camera-0.8 -i 127.0.0.1`, a real GVCP/GVSP
    peer on loopback; ./run installs aravis-tools, and its absence fails the test), as a factory:
    fake_gige_camera("pixel_format=Mono16&width=32") opens it with that URI query."""
    binary = shutil.which(FAKE_GIGE)
    assert binary, f"{FAKE_GIGE} not found: install aravis-tools (./run does)"
    # Only one device can bind 127.0.0.1:3956; the C++ tests take the same lock.
    with open("/tmp/tirpol-loopback-gige.lock", "a+") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        process = subprocess.Popen([binary, "-i", "127.0.0.1"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)

        def open_camera(query):
            deadline = time.monotonic() + 10.0
            while True:
                try:
                    return acquisition.open_camera(f"aravis://127.0.0.1?{query}")
                except tirpol.DeviceError:
                    assert time.monotonic() < deadline, "the fake camera did not answer within 10 s"
                    time.sleep(0.05)

        try:
            yield open_camera
        finally:
            process.terminate()
            process.wait()
