"""Per-pixel calibration of a microgrid (DoFP) camera from Python: numpy flat fields in, a
MicrogridPixelCalibration out, its prepared MicrogridPixelReducer giving Stokes with σ channels
whose stated σ matches the scatter of the estimates (pulls of standard deviation ≈ 1), and the
flat-field-session path of `tirpol calibrate microgrid` with the uncertainties it carries."""

import numpy as np
import pytest

import tirpol
from tirpol import calibration, core

SONY = np.array([[90.0, 45.0], [135.0, 0.0]])


def planted_camera(rng, height, width, spread=0.1):
    """Per pixel: transmission, diattenuation, axis (deg) about the Sony pattern, background."""
    t = rng.uniform(1 - spread, 1 + spread, (height, width))
    d = rng.uniform(0.98 - spread, 0.98, (height, width))
    theta = np.tile(SONY, (height // 2, width // 2)) + rng.normal(0, 10 * spread, (height, width))
    b = rng.uniform(0, 5, (height, width))
    return t, d, np.radians(theta), b


def record(camera, stokes, rng, sigma):
    t, d, theta, b = camera
    s0, s1, s2 = stokes
    clean = 0.5 * t * (s0 + d * (s1 * np.cos(2 * theta) + s2 * np.sin(2 * theta))) + b
    return (clean + rng.normal(0, sigma, clean.shape)).astype(np.float32)


def test_reducer_states_the_sigma_its_estimates_scatter_by():
    # The planted camera of the C++ test PropagatedSigmaMatchesTheScatterOverSeeds: a reference
    # polarizer at 8 angles × 2 radiances (16 flat fields, σ = 0.5 on the means), then a uniform
    # scene S = (300, 60, −45) with σ = 0.8 per pixel given as mosaic_std.
    rng = np.random.default_rng(7)
    height, width = 64, 64
    camera = planted_camera(rng, height, width)
    sources, frames = [], []
    for radiance in (200.0, 400.0):
        for phi in np.radians(np.arange(8) * 22.5):
            s = (radiance, radiance * np.cos(2 * phi), radiance * np.sin(2 * phi))
            sources.append(s)
            frames.append(record(camera, s, rng, 0.5))
    cal = calibration.calibrate_microgrid_pixels(np.array(sources), np.stack(frames))
    assert cal.has_uncertainties()
    assert (cal.width, cal.height) == (width, height)
    # The planted analyzers come back to the noise (σ ≈ 0.003 in d and t at these signals).
    assert np.sqrt(np.mean((cal.diattenuation - camera[1]) ** 2)) < 0.005
    assert np.sqrt(np.mean((cal.transmission - camera[0]) ** 2)) < 0.005

    truth = np.array([300.0, 60.0, -45.0])
    reducer = calibration.MicrogridPixelReducer(cal)
    mosaic = record(camera, truth, rng, 0.8)
    stokes = reducer.reduce(mosaic, np.full((height, width), 0.8, np.float32))
    assert stokes["S0"].shape == (height // 2, width // 2)
    assert stokes.attributes["std_includes"] == (
        "the frame's σ and the per-pixel calibration's fit error")
    truth_dolp = np.hypot(truth[1], truth[2]) / truth[0]
    # 1024 independent cells: the sample σ of N(0, 1) pulls is 1 ± 0.022; the calibration's σ is
    # itself estimated from 12 degrees of freedom, which puts the pulls' σ slightly above 1.
    for name, want in (("S0", truth[0]), ("S1", truth[1]), ("S2", truth[2]), ("DoLP", truth_dolp)):
        pulls = (stokes[name] - want) / stokes[name + "_std"]
        assert abs(pulls.mean()) < 0.1, name
        assert 0.9 < pulls.std() < 1.12, (name, pulls.std())
    # As many sources as parameters: no uncertainties, so without mosaic_std no σ channels.
    exact = calibration.calibrate_microgrid_pixels(np.array(sources[:3] + sources[8:9]),
                                                   np.stack(frames[:3] + frames[8:9]))
    assert not exact.has_uncertainties()
    assert "S0_std" not in calibration.MicrogridPixelReducer(exact).reduce(mosaic)
    with pytest.raises(tirpol.Error, match="shape"):
        reducer.reduce(mosaic[:, :-2])
    with pytest.raises(tirpol.Error, match="one frame per source"):
        calibration.calibrate_microgrid_pixels(np.array(sources), np.stack(frames[:-1]))


def test_flat_field_sessions_calibrate_and_reduce_a_session_with_uncertainties(tmp_path):
    band = core.Band(8.0, 14.0)
    s0 = band.radiance(300.0)
    scene = (s0, 0.3 * s0 * np.cos(np.radians(60)), 0.3 * s0 * np.sin(np.radians(60)))
    calibration.write_synthetic_microgrid_sessions(tmp_path, band, scene, analyzer_spread=0.2)
    result = calibration.calibrate_microgrid_sessions([tmp_path / "flat"], band)
    assert result["bad_count"] == 3  # the planted dead, hot and noisy pixels
    pixels = result["pixels"]
    assert pixels.has_uncertainties() and pixels.stokes_units == "W/(m^2 sr)"
    stokes = calibration.reduce_microgrid_session(tmp_path / "scene", pixel_calibration=pixels)
    dolp_error = np.sqrt(np.mean((stokes["DoLP"] - 0.3) ** 2))
    assert dolp_error < 0.002  # the 0.2 % with a 20 % analyzer spread
    # The stated σ is of the size of the error (not 0, not 10× it).
    assert 0.5 < dolp_error / np.sqrt(np.mean(stokes["DoLP_std"] ** 2)) < 2.0
    # The calibration survives its EXR file.
    path = tmp_path / "pixcal.exr"
    core.write_exr(str(path), pixels.to_image())
    back = calibration.MicrogridPixelCalibration.from_image(core.read_exr(str(path)))
    again = calibration.reduce_microgrid_session(tmp_path / "scene", pixel_calibration=back)
    np.testing.assert_array_equal(again["DoLP_std"], stokes["DoLP_std"])
