"""tirpol.simulation.sensor_images: the field camera's images I(α) behind its rotating wire grid
from a Stokes image. Checked against the analyzer model written out independently here — a linear
diattenuator with major/minor intensity transmittance τ, τ/ER at axis α + offset passes
I = ½[(τ + τ_min) S0 + (τ − τ_min)(S1 cos 2θ + S2 sin 2θ)], θ = α + offset (Chipman, Lam & Young,
"Polarized Light and Optical Systems", 2018, eq 6.35; Malus's law for τ_min = 0) — plus the grid's
reflection and emission; the four ideal images reduce back to the input (paper eqs 14–16); counts
carry the noise of the stated NEDT, σ = gain·NEDT·dL/dT(T_ref)."""

import numpy as np
import pytest

import tirpol
from tirpol import calibration, core, simulation

BAND = core.Band(8.0, 14.0)


def stokes_field(height=24, width=32):
    """S0 from 270 K to 310 K across the image, DoLP 0–20 % down it, AoP turning with x; S3 = 0.2 S0·DoLP."""
    y, x = np.mgrid[0:height, 0:width]
    s0 = BAND.radiance(270.0 + 40.0 * x / (width - 1))
    dolp = 0.2 * y / (height - 1)
    aop = np.deg2rad(180.0 * x / width)
    return {"S0": s0, "S1": s0 * dolp * np.cos(2 * aop), "S2": s0 * dolp * np.sin(2 * aop), "S3": 0.2 * s0 * dolp}


def analyzer(stokes, theta_deg, tau, extinction_ratio):
    t_min = tau / extinction_ratio
    theta = np.deg2rad(theta_deg)
    return 0.5 * ((tau + t_min) * stokes["S0"] + (tau - t_min) * (stokes["S1"] * np.cos(2 * theta)
                                                                    + stokes["S2"] * np.sin(2 * theta)))


def test_each_image_is_the_non_ideal_analyzer_seen_through_the_grid():
    stokes = stokes_field()
    model = {"analyzer": {"angles_deg": [0, 30, 45, 90, 135], "transmission": 0.7, "extinction_ratio": 400,
                          "angle_offset_deg": 1.5},
             "background": {"reflectance": 0.05, "reflected_radiance": 20.0, "emissivity": 0.02, "temperature": 293.15}}
    images = simulation.sensor_images(stokes, BAND, model)
    assert [i.attributes["polarizer_angle_deg"] for i in images] == [0, 30, 45, 90, 135]
    background = 0.05 * 20.0 + 0.02 * BAND.radiance(293.15)
    for image in images:
        alpha = image.attributes["polarizer_angle_deg"]
        assert list(image) == ["radiance"]
        expected = analyzer(stokes, alpha + 1.5, 0.7, 400.0) + background
        np.testing.assert_allclose(image["radiance"], expected, rtol=2e-6)
    # S3 is invisible to a linear analyzer: the same field without S3 gives the same images.
    no_s3 = dict(stokes, S3=np.zeros_like(stokes["S3"]))
    for a, b in zip(images, simulation.sensor_images(no_s3, BAND, model)):
        np.testing.assert_array_equal(a["radiance"], b["radiance"])


def test_ideal_images_follow_malus_and_reduce_back_to_the_input():
    stokes = stokes_field()
    model = {"analyzer": {"angles_deg": [0, 45, 90, 135], "transmission": 1.0, "extinction_ratio": 1e12}}
    images = simulation.sensor_images(stokes, BAND, model)
    for image in images:
        theta = np.deg2rad(image.attributes["polarizer_angle_deg"])
        malus = 0.5 * (stokes["S0"] + stokes["S1"] * np.cos(2 * theta) + stokes["S2"] * np.sin(2 * theta))
        np.testing.assert_allclose(image["radiance"], malus, rtol=2e-6)
    reduced = calibration.reduce({i.attributes["polarizer_angle_deg"]: i["radiance"] for i in images})
    for name in ("S0", "S1", "S2"):
        np.testing.assert_allclose(reduced[name], stokes[name], rtol=0, atol=2e-6 * stokes["S0"].max())


def test_counts_carry_the_noise_of_the_stated_nedt():
    stokes = {k: np.full((64, 64), v) for k, v in (("S0", BAND.radiance(300.0)), ("S1", 0.0), ("S2", 0.0), ("S3", 0.0))}
    model = {"analyzer": {"angles_deg": [0], "transmission": 1.0, "extinction_ratio": 1e12},
             "counts": {"gain_counts_per_radiance": 200, "offset_counts": 1000, "nedt_k": 0.05,
                        "reference_temperature": 300},
             "seed": 7}
    first = simulation.sensor_images(stokes, BAND, model, frame_index=0)[0]
    sigma = 200 * 0.05 * BAND.radiance_dT(300.0)
    assert first.attributes["counts_noise_sigma"] == pytest.approx(sigma, rel=1e-9)
    noise = first["counts"].astype(np.float64) - (200 * first["radiance"].astype(np.float64) + 1000)
    # 4096 samples: the mean within 5σ/√n, the standard deviation within 5·σ/√(2n).
    assert abs(noise.mean()) < 5 * sigma / 64
    assert noise.std() == pytest.approx(sigma, abs=5 * sigma / np.sqrt(2 * 4096))
    # Another frame index is another, independent draw; the same one is the same draw.
    again = simulation.sensor_images(stokes, BAND, model, frame_index=0)[0]
    np.testing.assert_array_equal(first["counts"], again["counts"])
    other = simulation.sensor_images(stokes, BAND, model, frame_index=1)[0]["counts"] - first["radiance"] * 200 - 1000
    assert abs(np.corrcoef(noise.ravel(), other.ravel())[0, 1]) < 5 / 64


def test_a_bad_model_names_its_key():
    with pytest.raises(tirpol.Error, match="extinction_ration"):
        simulation.sensor_images(stokes_field(), BAND, {"analyzer": {"extinction_ration": 100}})
    with pytest.raises(tirpol.Error, match="S3"):
        simulation.sensor_images({"S0": np.ones((2, 2)), "S1": np.zeros((2, 2)), "S2": np.zeros((2, 2))}, BAND)
