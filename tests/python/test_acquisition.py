# Requires TIRPOL_WITH_ARAVIS (registered only with that back end: cmake/TirpolBackends.cmake).
"""tirpol.acquisition from Python against Aravis's own fake GigE Vision camera
(`arv-fake-gv-camera-0.8 -i 127.0.0.1`, a real GVCP/GVSP peer on loopback; `./run` installs
aravis-tools, and its absence fails this test). Each frame must be the fake's published Mono16 test
pattern for its own frame id — Aravis 0.8.26 src/arvfakecamera.c arv_fake_camera_diagonal_ramp:
pixel (x, y) of frame id f is (256 x + 256 f + 256 y) mod 65535 — and ids must be consecutive."""

import os
import signal
import threading
import time

import numpy as np
import pytest

import tirpol
from tirpol import acquisition


@pytest.fixture()
def fake_camera(fake_gige_camera):
    camera = fake_gige_camera("pixel_format=Mono16")
    yield camera
    camera.stop()


def diagonal_ramp(width, height, unwrapped_id):
    raw_id = (unwrapped_id - 1) % 65535 + 1  # the pattern uses the device's 16-bit id
    y, x = np.mgrid[0:height, 0:width]
    return ((256 * x + 256 * raw_id + 256 * y) % 65535).astype(np.float32)


def test_frames_from_the_fake_gige_camera_are_its_test_pattern(fake_camera):
    info = fake_camera.info
    assert info["pixel_format"] == "Mono16" and info["vendor"] == "Aravis"
    with fake_camera:
        fake_camera.start()
        frames = [fake_camera.grab(timeout_s=5.0) for _ in range(8)]
    ids = [f["frame_id"] for f in frames]
    assert np.all(np.diff(ids) == 1), ids
    for f in frames:
        counts = f["counts"]
        assert counts.dtype == np.float32 and counts.shape == (info["height"], info["width"])
        np.testing.assert_array_equal(counts, diagonal_ramp(info["width"], info["height"], f["frame_id"]))
    assert fake_camera.statistics()["delivered"] >= 8


def test_device_errors_carry_their_code():
    with pytest.raises(tirpol.DeviceError) as error:
        acquisition.open_camera("aravis://No-Such-Camera-0")
    assert error.value.code == "disconnected" and "No-Such-Camera-0" in str(error.value)
    assert isinstance(error.value, tirpol.Error)
    with pytest.raises(tirpol.Error, match="nope"):
        acquisition.open_camera("nope://camera")


def test_simulated_camera_streams_its_uniform_level():
    camera = acquisition.open_camera("sim://uniform?width=16&height=12&counts=1000&noise=2&fps=200&seed=3")
    camera.start()
    stack = np.stack([camera.grab()["counts"] for _ in range(20)])
    camera.stop()
    assert stack.shape == (20, 12, 16)
    # Mean of 3840 samples of σ = 2 around 1000: within 5σ/√n = 0.16 counts.
    assert abs(stack.mean() - 1000.0) < 0.16
    assert stack.std() == pytest.approx(2.0, rel=0.1)


def test_timeouts_must_be_finite_non_negative_seconds():
    # grab(nan) said "no frame within -9223372036854775808 ms"; the argument is named as Python spells it.
    camera = acquisition.open_camera("sim://uniform?width=4&height=4&counts=1000&noise=0&fps=200&seed=1")
    stage = acquisition.open_stage("sim://?deg_per_s=720&start_deg=0")
    for bad in (float("nan"), float("inf"), -1.0, 1e300):
        with pytest.raises(ValueError, match=r"^timeout_s: expected a finite number of seconds in \[0, 600\]"):
            camera.grab(timeout_s=bad)
        with pytest.raises(ValueError, match=r"^timeout_s: expected a finite number of seconds in \[0, 3600\]"):
            stage.home(timeout_s=bad)
        with pytest.raises(ValueError, match=r"^timeout_s: "):
            stage.move_absolute(10.0, timeout_s=bad)
    with pytest.raises(ValueError, match=r"^angle_deg: expected a finite angle"):
        stage.move_absolute(float("nan"), timeout_s=10)


def test_stage_moves_and_reads_back():
    stage = acquisition.open_stage("sim://?deg_per_s=720&start_deg=0")
    stage.home(timeout_s=10)
    assert stage.is_homed
    stage.move_absolute(45.0, timeout_s=10)
    assert stage.position_deg() == pytest.approx(45.0, abs=0.01)


def test_ctrl_c_stops_a_stage_move_and_the_stage_stands_still():
    # 5 °/s: the move to 170° would take 34 s; a real SIGINT arrives after 0.5 s.
    stage = acquisition.open_stage("sim://?deg_per_s=5&start_deg=0")
    stage.home(timeout_s=10)
    timer = threading.Timer(0.5, os.kill, args=(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            stage.move_absolute(170.0, timeout_s=120)
    finally:
        timer.cancel()
    stopped_at = stage.position_deg()
    assert 0.0 < stopped_at < 170.0
    time.sleep(0.3)
    assert stage.position_deg() == pytest.approx(stopped_at, abs=1e-6), "the stage kept moving"
