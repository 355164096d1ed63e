"""Polarimetric calibration from arrays. The analyzer (AnalyzerModel.estimate): a non-ideal polarizer's
measurements of known sources, I_k = t_k·½(S0 + d_k(S1 cos 2θ_k + S2 sin 2θ_k)) + b_k (Chipman, Lam &
Young 2018 eq 6.35, normalised as calibration/analyzer.h), give back its planted axis angles,
extinction ratio, transmission and backgrounds. The wire grid (fit_wire_grid): blackbody frames through
the wire grid follow I(α) = τ(α)·½·L_band(T) + B(α) per pixel (calibration/wire_grid.h; Shaw & Descour
1995; the paper's §3.1 ghost and grid emission). Planted τ/B maps are recovered from frames at three
temperatures; with noise of known σ, the reported σ_τ, σ_B match the scatter of the estimates (pulls of
unit width); reducing scene images with the fitted grid gives back the planted Stokes field, which a
reduction without the grid misses."""

import numpy as np
import pytest

import tirpol
from tirpol import calibration, core

BAND = core.Band(8.0, 14.0)
ANGLES = (0.0, 45.0, 90.0, 135.0)
TEMPERATURES = (283.15, 303.15, 323.15)
HEIGHT, WIDTH = 40, 56


def planted_grid():
    """τ 0.6 … 0.8 across the image, a ghost B of 0.5 … 1.5 W/(m² sr) down it, different per angle."""
    y, x = np.mgrid[0:HEIGHT, 0:WIDTH]
    tau = {a: 0.6 + 0.2 * x / (WIDTH - 1) + 0.01 * k for k, a in enumerate(ANGLES)}
    background = {a: 0.5 + y / (HEIGHT - 1) + 0.1 * k for k, a in enumerate(ANGLES)}
    return tau, background


def blackbody_frames(tau, background, sigma=0.0, seed=1):
    rng = np.random.default_rng(seed)
    return {(a, t): tau[a] * 0.5 * BAND.radiance(t) + background[a] + sigma * rng.normal(size=(HEIGHT, WIDTH))
            for a in ANGLES for t in TEMPERATURES}


def test_noise_free_frames_give_back_the_planted_maps():
    tau, background = planted_grid()
    grid = calibration.fit_wire_grid(blackbody_frames(tau, background), BAND)
    assert grid.angles_deg == list(ANGLES) and (grid.height, grid.width) == (HEIGHT, WIDTH)
    for a in ANGLES:
        np.testing.assert_allclose(grid.tau(a), tau[a], rtol=1e-5)
        np.testing.assert_allclose(grid.background(a), background[a], rtol=0, atol=1e-4)
        assert grid.residual_rms(a).max() < 1e-4


def test_reported_uncertainties_match_the_scatter_of_the_estimates():
    tau, background = planted_grid()
    sigma = 0.05  # W/(m² sr) per frame mean
    frames = blackbody_frames(tau, background, sigma)
    stds = {key: np.full((HEIGHT, WIDTH), sigma) for key in frames}
    grid = calibration.fit_wire_grid(frames, BAND, stds=stds)
    for a in ANGLES:
        pull_tau = (grid.tau(a) - tau[a]) / grid.tau_std(a)
        pull_b = (grid.background(a) - background[a]) / grid.background_std(a)
        # 2240 pixels: the pulls have mean 0 ± 5/√n and unit width within 10 %.
        for pull in (pull_tau, pull_b):
            assert abs(pull.mean()) < 5 / np.sqrt(pull.size)
            assert pull.std() == pytest.approx(1.0, rel=0.1)


def test_reduction_with_the_fitted_grid_recovers_the_scene():
    tau, background = planted_grid()
    grid = calibration.fit_wire_grid(blackbody_frames(tau, background), BAND)
    s0 = np.full((HEIGHT, WIDTH), BAND.radiance(295.0))
    s1, s2 = -0.03 * s0, 0.01 * s0
    scene = {a: tau[a] * 0.5 * (s0 + s1 * np.cos(np.deg2rad(2 * a)) + s2 * np.sin(np.deg2rad(2 * a))) + background[a]
             for a in ANGLES}
    stokes = calibration.reduce(scene, wire_grid=grid)
    for name, truth in (("S0", s0), ("S1", s1), ("S2", s2)):
        np.testing.assert_allclose(stokes[name], truth, rtol=0, atol=1e-3)
    # Without the grid the ghost and the transmittance stay in: S0 is off by far more than that.
    assert np.abs(calibration.reduce(scene)["S0"] - s0).min() > 0.5


def test_bad_frames_are_named():
    tau, background = planted_grid()
    frames = blackbody_frames(tau, background)
    one_temperature = {k: v for k, v in frames.items() if k[1] == TEMPERATURES[0]}
    with pytest.raises(tirpol.Error, match="temperature"):
        calibration.fit_wire_grid(one_temperature, BAND)
    with pytest.raises(tirpol.Error, match=r"stds: no array for frames\[\(0, 283.15\)\]"):
        calibration.fit_wire_grid(frames, BAND, stds={})
    grid = calibration.fit_wire_grid(frames, BAND)
    with pytest.raises(tirpol.Error, match="no covariance"):
        grid.tau_std(0.0)
    with pytest.raises(tirpol.Error, match="22.5"):
        grid.tau(22.5)


def test_the_analyzer_is_estimated_from_known_sources():
    # Planted: extinction ratio 100 (d = 99/101), axes 1.5° off, t = t_max + t_min = 0.8 + 0.008, and
    # a background per position. Sources: two unpolarized levels and fully polarized light at 0°, 60°, 120°.
    d, t, offset_deg, b = 99.0 / 101.0, 0.808, 1.5, np.array([0.3, 0.2, 0.1, 0.4])
    polarized = [[30.0, 30.0 * np.cos(np.deg2rad(2 * psi)), 30.0 * np.sin(np.deg2rad(2 * psi))] for psi in (0, 60, 120)]
    stokes = np.array([[20.0, 0.0, 0.0], [40.0, 0.0, 0.0]] + polarized)
    theta = np.deg2rad(2 * (np.array(ANGLES) + offset_deg))
    intensities = t * 0.5 * (stokes[:, :1] + d * (stokes[:, 1:2] * np.cos(theta) + stokes[:, 2:3] * np.sin(theta))) + b
    model = calibration.AnalyzerModel.estimate(list(ANGLES), stokes, intensities)
    for k, position in enumerate(model.positions):
        assert position.nominal_angle_deg == ANGLES[k]
        assert position.axis_angle_deg == pytest.approx(ANGLES[k] + offset_deg, abs=1e-9)
        assert position.extinction_ratio == pytest.approx(100.0, rel=1e-9)
        assert position.relative_transmission == pytest.approx(t, rel=1e-12)
        assert position.background == pytest.approx(b[k], abs=1e-9)
    # Three sources cannot determine the four unknowns per position: refused.
    with pytest.raises(tirpol.Error):
        calibration.AnalyzerModel.estimate(list(ANGLES), stokes[:3], intensities[:3])
    with pytest.raises(tirpol.Error, match=r"intensities: expected shape \(5, 4\)"):
        calibration.AnalyzerModel.estimate(list(ANGLES), stokes, intensities[:, :3])
