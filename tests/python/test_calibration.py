"""tirpol.calibration.reduce from numpy arrays: analyzer images made with core's Mueller matrices
(Malus's law) reduce back to the Stokes field they came from, in the convention S1 = I0 − I90,
S2 = I45 − I135 (Gartley et al. eqs 14–16), with first-order propagated uncertainties."""

import math

import numpy as np
import pytest

import tirpol
from tirpol import calibration, core


def stokes_field(height=24, width=32):
    y, x = np.mgrid[0:height, 0:width]
    s0 = 20.0 + 0.1 * x
    dolp = 0.02 + 0.3 * y / height
    aop = np.radians(5.0 * x)
    return np.stack([s0, s0 * dolp * np.cos(2 * aop), s0 * dolp * np.sin(2 * aop), np.zeros_like(s0)], axis=-1)


def analyzer_images(s, angles_deg):
    # I(α) = first row of the polarizer's Mueller matrix times S: what the camera behind it sees.
    return {a: (s @ core.linear_polarizer(a)[0]).astype(np.float32) for a in angles_deg}


@pytest.mark.parametrize("angles_deg", [(0.0, 45.0, 90.0, 135.0), (0.0, 60.0, 120.0), (10.0, 50.0, 95.0, 130.0, 170.0)])
def test_reduce_recovers_the_stokes_field(angles_deg):
    s = stokes_field()
    result = calibration.reduce(analyzer_images(s, angles_deg))
    assert isinstance(result, tirpol.Image) and result.shape == (24, 32)
    for k, name in enumerate(("S0", "S1", "S2")):
        np.testing.assert_allclose(result[name], s[..., k], rtol=0, atol=2e-5 * 40)
    np.testing.assert_allclose(result["DoLP"], core.dolp(s), atol=1e-5)
    assert result.attributes["analyzer_angles_deg"] == list(angles_deg)


def test_eqs_14_to_16_for_the_four_angle_set():
    i0, i45, i90, i135 = (np.full((2, 2), v, np.float32) for v in (3.0, 2.0, 1.0, 2.5))
    result = calibration.reduce({0: i0, 45: i45, 90: i90, 135: i135}, project_to_realizable=False)
    np.testing.assert_allclose(result["S0"], (3 + 2 + 1 + 2.5) / 2)  # eq 14 (mean of the two pairs)
    np.testing.assert_allclose(result["S1"], 3 - 1)  # eq 15
    np.testing.assert_allclose(result["S2"], 2 - 2.5)  # eq 16


def test_uncertainties_propagate_through_the_drm():
    # With σ per angle: S0 = ½ΣI → σ(S0) = ½·√4·σ = σ; S1 = I0 − I90 → √2·σ (ideal 0/45/90/135).
    s = stokes_field(8, 8)
    images = analyzer_images(s, (0, 45, 90, 135))
    sigma = 0.05
    stds = {a: np.full((8, 8), sigma, np.float32) for a in images}
    result = calibration.reduce(images, stds)
    np.testing.assert_allclose(result["S0_std"], sigma, rtol=1e-5)
    np.testing.assert_allclose(result["S1_std"], math.sqrt(2) * sigma, rtol=1e-5)
    np.testing.assert_allclose(result["S2_std"], math.sqrt(2) * sigma, rtol=1e-5)


def test_non_ideal_analyzer_model_is_inverted():
    # A wire grid with extinction ratio 400 and a 2° axis offset (paper §3.1): images made with its
    # Mueller matrices reduce to the true field only with that model.
    s = stokes_field()
    angles = (0.0, 45.0, 90.0, 135.0)
    model = calibration.AnalyzerModel.non_ideal(list(angles), 400.0, 2.0)
    images = {a: (s @ core.polarizer_with_extinction(a + 2.0, 1.0, 400.0)[0]).astype(np.float32) for a in angles}
    np.testing.assert_allclose(calibration.reduce(images, model=model)["S1"], s[..., 1], atol=1e-3)
    ideal = calibration.reduce(images)["S1"]
    assert np.max(np.abs(ideal - s[..., 1])) > 1e-2


def test_reduce_rejects_bad_input_with_clear_messages():
    with pytest.raises(tirpol.Error, match="shape"):
        calibration.reduce({0: np.zeros((4, 4)), 45: np.zeros((4, 5)), 90: np.zeros((4, 4))})
    with pytest.raises(tirpol.Error, match="stds: no array for angle 90"):
        calibration.reduce({0: np.ones((2, 2)), 45: np.ones((2, 2)), 90: np.ones((2, 2))},
                           {0: np.ones((2, 2)), 45: np.ones((2, 2))})
    with pytest.raises(tirpol.Error):
        calibration.reduce({0: np.ones((2, 2)), 180: np.ones((2, 2)), 90: np.ones((2, 2))})  # rank-deficient W


def test_demosaic_and_reduce_microgrid_recover_a_uniform_polarized_field_from_numpy():
    # Sony IMX250MZR layout: (0,0)=90°, (0,1)=45°, (1,0)=135°, (1,1)=0°. A field polarized at 30°
    # with S0 = 100, DoLP 0.4: each pixel holds ½(S0 + S1 cos 2θ + S2 sin 2θ) (float, no rounding).
    s0, s1, s2 = 100.0, 40.0 * np.cos(np.radians(60)), 40.0 * np.sin(np.radians(60))
    angles = np.array([[90.0, 45.0], [135.0, 0.0]])
    theta = np.radians(np.tile(angles, (8, 10)))
    mosaic = (0.5 * (s0 + s1 * np.cos(2 * theta) + s2 * np.sin(2 * theta))).astype(np.float32)
    planes = calibration.demosaic(mosaic, pattern="sony", method="bilinear")
    assert sorted(planes) == [0.0, 45.0, 90.0, 135.0]
    for angle, plane in planes.items():
        assert plane.shape == (16, 20)
        want = 0.5 * (s0 + s1 * np.cos(np.radians(2 * angle)) + s2 * np.sin(np.radians(2 * angle)))
        np.testing.assert_allclose(plane, want, rtol=1e-5)
    assert calibration.demosaic(mosaic, method="super-pixel")[0.0].shape == (8, 10)
    stokes = calibration.reduce_microgrid(mosaic, pattern=[90, 45, 135, 0], method="newton")
    np.testing.assert_allclose(stokes["S1"], s1, atol=1e-3)
    np.testing.assert_allclose(stokes["DoLP"], 0.4, atol=1e-5)
    np.testing.assert_allclose(stokes["AoP"], 30.0, atol=1e-3)
    with pytest.raises(tirpol.Error, match="pattern"):
        calibration.demosaic(mosaic, pattern="0,1,2,3")
    with pytest.raises(tirpol.Error, match="method"):
        calibration.demosaic(mosaic, method="cubic")
