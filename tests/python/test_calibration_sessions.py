"""tirpol.calibration on sessions and counts: the synthetic sessions of calibration/synthetic_session.h
(a simulated uncooled camera, a 100:1 wire grid offset by 1.5°, a panel with ε_S1 = −0.035) go
through radiometric calibration, polarimetric calibration, reduction and emissivity extraction, and
the planted truth comes back within the propagated uncertainties (as tests/calibration/session_calibration_test.cpp);
temperature from counts inverts a per-pixel radiometric model fitted from arrays."""

import numpy as np
import pytest

import tirpol
from tirpol import calibration, core

BAND = core.Band(8.0, 14.0)


@pytest.fixture(scope="module")
def sessions(tmp_path_factory):
    root = tmp_path_factory.mktemp("sessions")
    truth = calibration.write_synthetic_sessions(root, BAND)
    return root, truth


def test_session_pipeline_recovers_the_planted_scene(sessions):
    root, truth = sessions
    radiometric = calibration.calibrate_radiometric_session(root / "lab", BAND)
    assert (radiometric.height, radiometric.width) == (48, 64)
    assert radiometric.bad_count() == 3  # the planted dead, hot and noisy pixels
    assert radiometric.bad[5, 5] != 0 and radiometric.bad[30, 9] != 0 and radiometric.bad[12, 40] != 0
    polarimetric = calibration.calibrate_polarimetric_session(root / "polcal", radiometric)
    assert polarimetric.analyzer_method == "known-source least squares"
    for p in polarimetric.analyzer.positions:
        assert p.axis_angle_deg - p.nominal_angle_deg == pytest.approx(1.5, abs=0.2)
        assert p.extinction_ratio == pytest.approx(100.0, abs=20.0)
    stokes = calibration.reduce_session(root / "scene", radiometric, polarimetric)
    panel = (slice(12, 36), slice(26, 38))
    error = stokes["S1"][panel] - truth["S1"][panel]
    assert np.all(np.abs(error) <= 5 * stokes["S1_std"][panel] + 1e-3)
    assert abs(error.mean()) < 4 * 0.04 / np.sqrt(error.size)
    assert stokes["S0"][20, 30] == pytest.approx(truth["S0"][20, 30], abs=0.15)
    assert stokes.attributes["saturated_pixels"] == 0
    # Emissivity of the panel (paper eq 17) against its planted ε: reflector x 4..15, panel x 24..39.
    [panel_eps] = calibration.extract_emissivity(
        stokes, reflector=[5, 10, 9, 28], band=BAND,
        targets=[{"name": "panel", "rect": [26, 12, 12, 24], "view_angle_deg": 45.0, "temperature_k": 300.0,
                  "temperature_std_k": 0.05}])
    assert panel_eps["eps_s0"] == pytest.approx(0.93, abs=max(2 * panel_eps["eps_s0_std"], 0.005))
    assert panel_eps["eps_s1"] == pytest.approx(-0.035, abs=max(2 * panel_eps["eps_s1_std"], 0.002))
    assert panel_eps["eps_s2"] == pytest.approx(0.01, abs=max(2 * panel_eps["eps_s2_std"], 0.002))


def test_run_chain_is_the_step_functions_in_the_order_of_the_library(sessions):
    # calibration_chain.h: one ordered list of steps that the CLI, the demo, the twin and run_chain use.
    root, _ = sessions
    assert [s["name"] for s in calibration.calibration_steps()] == ["radiometric", "polarimetric", "reduce",
                                                                   "emissivity"]
    regions = {"reflector": [5, 10, 9, 28],
               "targets": [{"name": "panel", "rect": [26, 12, 12, 24], "view_angle_deg": 45.0,
                            "temperature_k": 300.0, "temperature_std_k": 0.05}]}
    chain = calibration.run_chain(BAND, blackbody_sessions=[root / "lab"], polarimetric_session=root / "polcal",
                                  scene_sessions=[root / "scene"], regions=[regions])
    radiometric = calibration.calibrate_radiometric_session(root / "lab", BAND)
    polarimetric = calibration.calibrate_polarimetric_session(root / "polcal", radiometric)
    stokes = calibration.reduce_session(root / "scene", radiometric, polarimetric)
    np.testing.assert_array_equal(chain["radiometric"].gain, radiometric.gain)
    assert chain["polarimetric"].analyzer_method == polarimetric.analyzer_method
    for c in ("S0", "S1", "S2", "S0_std", "S1_std", "S2_std"):
        np.testing.assert_array_equal(chain["stokes"][0][c], stokes[c])
    [[row]] = chain["emissivity"]
    assert row == calibration.extract_emissivity(stokes, band=BAND, **regions)[0]
    # A calibration given (read from its file) skips its step: only the reduction runs, ideal analyzer.
    again = calibration.run_chain(BAND, scene_sessions=[root / "scene"], radiometric=chain["radiometric"],
                                  update_offset=True)
    assert again["polarimetric"] is None and again["emissivity"] == []
    np.testing.assert_array_equal(again["stokes"][0]["S1"],
                                  calibration.reduce_session(root / "scene", radiometric, update_offset=True)["S1"])
    with pytest.raises(tirpol.Error, match="step 'reduce': needs a radiometric calibration"):
        calibration.run_chain(BAND, scene_sessions=[root / "scene"])


def test_without_the_wire_grid_calibration_the_sky_reflection_biases_s1(sessions):
    root, truth = sessions
    radiometric = calibration.calibrate_radiometric_session(root / "lab", BAND)
    naive = calibration.reduce_session(root / "scene", radiometric, update_offset=True)
    assert abs(naive["S1"][20, 30] - truth["S1"][20, 30]) > 0.3


def test_temperature_from_counts_inverts_a_fitted_radiometric_model():
    rng = np.random.default_rng(5)
    gain = rng.uniform(80.0, 120.0, size=(16, 20))  # counts per W/(m² sr)
    offset = rng.uniform(4000.0, 6000.0, size=(16, 20))
    frames = {t: offset + gain * BAND.radiance(t) for t in (283.0, 303.0, 323.0)}
    cal = calibration.fit_radiometric(frames, BAND)
    np.testing.assert_allclose(cal.gain, gain, rtol=1e-4)
    scene_k = np.linspace(270.0, 330.0, 16 * 20).reshape(16, 20)
    counts = (offset + gain * BAND.radiance(scene_k)).astype(np.float32)
    # float32 counts of ~6000 carry ±0.0005 counts: ≈ 1e-4 K at these gains.
    np.testing.assert_allclose(cal.temperature_from_counts(counts), scene_k, atol=5e-3)
    with pytest.raises(tirpol.Error, match=r"counts: shape \(3, 3\) differs"):
        cal.temperature_from_counts(np.zeros((3, 3)))


def test_radiometric_calibration_file_round_trip(tmp_path):
    frames = {t: 5000.0 + 100.0 * BAND.radiance(t) * np.ones((4, 5)) for t in (283.0, 323.0)}
    cal = calibration.fit_radiometric(frames, BAND)
    cal.write(str(tmp_path / "radiometric.exr"))
    back = calibration.read_radiometric_calibration(str(tmp_path / "radiometric.exr"))
    np.testing.assert_array_equal(back.gain, cal.gain)
    assert back.temperatures_k == [283.0, 323.0]


def test_three_d_noise_separates_planted_components():
    # D'Agostino & Webb (1991): a cube with a frame flicker, fixed row and column patterns and white
    # noise. Each planted pattern is exactly zero-mean, so its population σ comes back up to the
    # white noise's leak into that average (σ_tvh/√(pixels averaged)); the seven population variances
    # add up exactly to the cube's variance.
    rng = np.random.default_rng(2)
    t, v, h = 40, 32, 48

    def zero_mean(n, s):
        x = rng.normal(size=n) * s
        return x - x.mean()

    flicker, rows, cols = zero_mean(t, 0.5), zero_mean(v, 0.8), zero_mean(h, 0.3)
    cube = 1000.0 + flicker[:, None, None] + rows[None, :, None] + cols[None, None, :] + rng.normal(size=(t, v, h))
    n = calibration.three_d_noise(cube.astype(np.float32))
    assert n["mean"] == pytest.approx(1000.0, abs=0.01)
    assert n["sigma_t"] == pytest.approx(flicker.std(), abs=3 / np.sqrt(v * h))
    assert n["sigma_v"] == pytest.approx(rows.std(), abs=3 / np.sqrt(t * h))
    assert n["sigma_h"] == pytest.approx(cols.std(), abs=3 / np.sqrt(t * v))
    # The white noise's variance is shared among the components by their degrees of freedom: N_tvh
    # keeps (t−1)(v−1)(h−1)/(t·v·h) of it.
    assert n["sigma_tvh"] == pytest.approx(np.sqrt((t - 1) * (v - 1) * (h - 1) / (t * v * h)), abs=0.01)
    parts = sum(n[f"sigma_{k}"] ** 2 for k in ("t", "v", "h", "tv", "th", "vh", "tvh"))
    assert parts == pytest.approx(cube.astype(np.float32).astype(np.float64).var(), rel=1e-4)
    assert n["sigma_total"] ** 2 == pytest.approx(parts, rel=1e-9)
    temporal = calibration.temporal_noise(cube)
    assert temporal.shape == (v, h) and np.median(temporal) == pytest.approx(np.sqrt(1 + 0.25), rel=0.1)
