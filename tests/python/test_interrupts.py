"""Ctrl-C stops the long calls (docs/python.md, "Long calls"): a real SIGINT sent to this process
while the call runs sets the C++ cancellation flag (checked per Ceres iteration, per image row,
per record, between comparison stages), the call ends with KeyboardInterrupt once its worker has
returned, and the next call runs normally. Each workload takes far longer than the time to the signal
on an idle machine, so an uninterruptible call fails the test by returning."""

import os
import signal
import threading

import numpy as np
import pytest

from tirpol import calibration, core, fitting, report

BAND = core.Band(8.0, 14.0)


def interrupted(call, after_s=0.5):
    timer = threading.Timer(after_s, os.kill, args=(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            call()
    finally:
        timer.cancel()


def test_ctrl_c_stops_a_fit():
    angle_deg = np.arange(0.0, 81.0, 10.0)
    e_s0, e_s1, sigma = np.full(9, 0.95), -0.01 * angle_deg / 80.0, np.full(9, 0.002)
    # 10 000 starts, the most the limits table allows: hours of work (20 starts took 15 s on a loaded machine).
    interrupted(lambda: fitting.fit_microfacet(angle_deg, e_s0, sigma, e_s1, sigma, starts=10_000))
    assert fitting.fit_microfacet(angle_deg, e_s0, sigma, e_s1, sigma, starts=1).chi2 >= 0.0


def test_ctrl_c_stops_a_reduction():
    # 8 analyzer angles of 2000×2000 with σ images: ≈ 1.3 s of work, cancellation checked per row.
    angles = np.arange(0.0, 180.0, 22.5)
    level = np.full((2000, 2000), 10.0, np.float32)
    images = {a: level for a in angles}
    stds = {a: np.full_like(level, 0.1) for a in angles}
    interrupted(lambda: calibration.reduce(images, stds), after_s=0.1)
    small = {a: level[:8, :8] for a in angles}
    np.testing.assert_allclose(calibration.reduce(small)["S0"], 20.0, rtol=1e-6)


def test_ctrl_c_stops_a_session_reduction(tmp_path):
    calibration.write_synthetic_sessions(tmp_path, BAND, width=640, height=512)
    radiometric = calibration.calibrate_radiometric_session(tmp_path / "lab", BAND)
    # ≈ 0.4 s of reading and reducing 640×512 records on the shared machine.
    interrupted(lambda: calibration.reduce_session(tmp_path / "scene", radiometric), after_s=0.05)
    assert calibration.reduce_session(tmp_path / "scene", radiometric)["S0"].shape == (512, 640)


def test_ctrl_c_stops_a_comparison():
    rng = np.random.default_rng(2)
    y, x = np.mgrid[0:1536, 0:2048]
    s0 = 30.0 + np.sin(x / 40.0) * np.cos(y / 30.0)
    simulated = {"S0": s0, "S1": 0.01 * s0, "S2": 0.0 * s0}
    measured = {k: v + 0.01 * rng.normal(size=v.shape) for k, v in simulated.items()}
    # ≈ 9 s of automatic registration (ECC, checked per pyramid level) and statistics at 2048×1536.
    interrupted(lambda: report.compare(measured, simulated, registration="auto"), after_s=0.3)
    small = {k: v[:64, :64] for k, v in measured.items()}, {k: v[:64, :64] for k, v in simulated.items()}
    assert "regions" in report.compare(*small, registration="none").statistics
