# Requires TIRPOL_WITH_ARAVIS (registered only with that back end: cmake/TirpolBackends.cmake).
"""tirpol.acquisition.run_capture end to end: Aravis's fake GigE Vision camera (conftest
fake_gige_camera) looking through the APT stage simulator `tirpol-stage-sim` on a pseudo-terminal (a
separate process, opened by the real serial driver), as the C++ capture tests run them. Each
record must be the mean and sample σ of exactly the frames the progress callback reported (the
fake's published ramp for their ids, test_acquisition.diagonal_ramp); a Python exception in the
callback and a real SIGINT stop the capture with a resumable session, and Ctrl-C mid-move leaves
the stage standing where it was stopped."""

import json
import os
import pathlib
import signal
import subprocess
import threading
import time

import numpy as np
import pytest

import tirpol
from test_acquisition import diagonal_ramp
from tirpol import acquisition, core

CAMERA_QUERY = "pixel_format=Mono16&width=32&height=16&fps=50"
PLAN = {"angles_deg": [0, 90], "frames_per_angle": 4, "settle_s": 0.1, "repeats": 2, "move_timeout_s": 30}


@pytest.fixture()
def apt_stage(tmp_path):
    """tirpol-stage-sim speaking APT at 30 °/s (a 90° move takes 3 s), as a factory of connections."""
    binary = os.environ.get("TIRPOL_STAGE_SIM")
    assert binary and os.access(binary, os.X_OK), "TIRPOL_STAGE_SIM is not the stage simulator (ctest sets it)"
    link = tmp_path / "stage"
    process = subprocess.Popen([binary, "--protocol", "apt", "--link", str(link), "--move-deg-per-s", "30"],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 10.0
        while not link.exists():
            assert time.monotonic() < deadline, "the stage simulator did not create its pty within 10 s"
            time.sleep(0.01)
        yield lambda: acquisition.open_stage(f"thorlabs-apt://{link}")
    finally:
        process.terminate()
        process.wait()


def manifest(session_dir):
    return json.loads((pathlib.Path(session_dir) / "session.json").read_text())


def test_each_record_is_the_mean_of_the_frames_the_callback_reported(fake_gige_camera, apt_stage, tmp_path):
    camera, stage = fake_gige_camera(CAMERA_QUERY), apt_stage()
    events = []
    summary = acquisition.run_capture(PLAN, camera, stage, tmp_path / "session", progress=events.append)
    assert summary["steps_total"] == summary["steps_recorded"] == 4 and summary["frames"] == 16

    m = manifest(tmp_path / "session")
    assert m["complete"] and len(m["records"]) == 4
    for index, record in enumerate(m["records"]):
        frames = [e for e in events if e["event"] == "frame" and e["step"] == index]
        recorded = [e for e in events if e["event"] == "step" and e["step"] == index]
        assert [e["frames_kept"] for e in frames] == [1, 2, 3, 4]
        assert len(recorded) == 1 and recorded[0]["steps_recorded"] == index + 1
        assert recorded[0]["file"] == record["file"] and recorded[0]["angle_deg"] == record["angle_deg_requested"]
        stack = np.stack([diagonal_ramp(32, 16, e["frame_id"]).astype(np.float64) for e in frames])
        image = core.read_exr(tmp_path / "session" / record["file"])
        np.testing.assert_allclose(image["counts"], stack.mean(axis=0), rtol=0, atol=1e-3)
        np.testing.assert_allclose(image["counts_std"], stack.std(axis=0, ddof=1), rtol=1e-5, atol=1e-3)
        assert abs(record["angle_deg_measured"] - record["angle_deg_requested"]) <= 0.05
    # Steps in plan order, each step's event after its frames.
    assert [e["step"] for e in events if e["event"] == "step"] == [0, 1, 2, 3]


def test_an_exception_in_the_callback_stops_the_capture_and_the_session_resumes(fake_gige_camera, apt_stage, tmp_path):
    camera, stage = fake_gige_camera(CAMERA_QUERY), apt_stage()

    def stop_in_the_second_step(event):
        if event["step"] == 1 and event.get("frames_kept") == 2:
            raise ValueError("enough for today")

    with pytest.raises(ValueError, match="enough for today"):
        acquisition.run_capture(PLAN, camera, stage, tmp_path / "session", progress=stop_in_the_second_step)
    first = manifest(tmp_path / "session")
    assert not first["complete"] and len(first["records"]) == 1

    summary = acquisition.run_capture(PLAN, camera, stage, tmp_path / "session", resume=True)
    assert summary["steps_already_recorded"] == 1 and summary["steps_recorded"] == 3
    m = manifest(tmp_path / "session")
    assert m["complete"] and m["records"][0] == first["records"][0]


def test_ctrl_c_during_a_move_stops_the_stage_and_the_session_resumes(fake_gige_camera, apt_stage, tmp_path):
    camera, stage = fake_gige_camera(CAMERA_QUERY), apt_stage()

    timer = threading.Timer(1.0, os.kill, args=(os.getpid(), signal.SIGINT))

    def interrupt_after_the_first_step(event):
        # A real SIGINT to this process 1 s after step 1 is recorded: during the 3 s move to 90°.
        if event["event"] == "step" and event["step"] == 0:
            timer.start()

    try:
        with pytest.raises(KeyboardInterrupt):
            acquisition.run_capture(PLAN, camera, stage, tmp_path / "session", progress=interrupt_after_the_first_step)
    finally:
        timer.cancel()
    m = manifest(tmp_path / "session")
    assert not m["complete"] and len(m["records"]) == 1
    # The move was stopped part-way and the stage stays there.
    stopped_at = stage.position_deg()
    assert 0.0 < stopped_at < 89.0
    time.sleep(0.5)
    assert stage.position_deg() == pytest.approx(stopped_at, abs=1e-3), "the stage kept moving"

    summary = acquisition.run_capture(PLAN, camera, stage, tmp_path / "session", resume=True)
    assert summary["steps_already_recorded"] == 1 and summary["steps_recorded"] == 3
    assert manifest(tmp_path / "session")["complete"]


def test_a_bad_plan_names_its_field(fake_gige_camera, apt_stage, tmp_path):
    camera, stage = fake_gige_camera(CAMERA_QUERY), apt_stage()
    with pytest.raises(tirpol.Error, match="frames_per_angel"):
        acquisition.run_capture({"frames_per_angel": 4}, camera, stage, tmp_path / "session")
    assert not (tmp_path / "session").exists()


def test_list_cameras_finds_the_fake_gige_camera(fake_gige_camera):
    fake_gige_camera(CAMERA_QUERY)  # started and answering
    cameras = acquisition.list_cameras()
    fake = [c for c in cameras if c["uri"].startswith("aravis://") and "127.0.0.1" in c["description"]]
    assert fake, cameras
    with acquisition.open_camera(fake[0]["uri"] + "?pixel_format=Mono16") as camera:
        assert camera.info["vendor"] == "Aravis"
