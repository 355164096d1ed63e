"""NEDT from arrays (tirpol.calibration.nedt_map, nedt_vs_averaging) against synthetic frame stacks
of known noise: a stack of a uniform source with white Gaussian noise of σ counts per pixel, seen with
responsivity r counts/K, has NEDT = σ/r (the definition: the temperature difference whose signal
equals the temporal noise); the sample σ of n frames scatters by σ/√(2(n − 1)) per pixel. Averaging n
frames of white noise divides the NEDT by √n; a random-walk drift does not average away."""

import numpy as np
import pytest

import tirpol
from tirpol import calibration

FRAMES, HEIGHT, WIDTH = 200, 48, 64


def test_nedt_of_white_noise_is_sigma_over_responsivity():
    rng = np.random.default_rng(5)
    # Responsivity varies across columns (20 … 40 counts/K) and the noise with it: NEDT 0.05 K everywhere.
    responsivity = np.tile(np.linspace(20.0, 40.0, WIDTH), (HEIGHT, 1))
    frames = 8000.0 + 0.05 * responsivity * rng.normal(size=(FRAMES, HEIGHT, WIDTH))
    nedt = calibration.nedt_map(frames, responsivity)
    assert nedt.shape == (HEIGHT, WIDTH) and nedt.dtype == np.float32
    spread = 0.05 / np.sqrt(2 * (FRAMES - 1))  # σ of one pixel's estimate
    pixels = HEIGHT * WIDTH
    assert nedt.mean() == pytest.approx(0.05, abs=5 * spread / np.sqrt(pixels))
    assert nedt.std() == pytest.approx(spread, rel=0.1)
    # No trend with the responsivity: the noise was scaled to it.
    assert abs(np.corrcoef(nedt.ravel(), responsivity.ravel())[0, 1]) < 5 / np.sqrt(pixels)
    # A uniform responsivity may be a number.
    uniform = calibration.nedt_map(8000.0 + 2.0 * rng.normal(size=(FRAMES, 8, 8)), 25.0)
    assert np.median(uniform) == pytest.approx(2.0 / 25.0, rel=0.05)


def test_averaging_divides_white_noise_by_sqrt_n_but_not_a_drift():
    rng = np.random.default_rng(6)
    white = 5000.0 + 3.0 * rng.normal(size=(256, 16, 16))
    curve = calibration.nedt_vs_averaging(white, 30.0)
    assert [p["frames_averaged"] for p in curve] == [1, 2, 4, 8, 16, 32, 64]
    assert curve[0]["median_nedt_k"] == pytest.approx(0.1, rel=0.05)
    for p in curve:
        assert p["white_noise_k"] == pytest.approx(curve[0]["median_nedt_k"] / np.sqrt(p["frames_averaged"]))
        # 256/n means per pixel: the median σ over 256 pixels is within 20 % at n = 64 (4 means).
        assert p["median_nedt_k"] == pytest.approx(p["white_noise_k"], rel=0.2 if p["frames_averaged"] < 64 else 0.35)
    # The same noise plus a common random-walk offset (1/f-like drift of 0.5 counts per frame).
    drift = np.cumsum(0.5 * rng.normal(size=256))[:, None, None]
    drifting = calibration.nedt_vs_averaging(white + drift, 30.0)
    assert drifting[-1]["median_nedt_k"] > 2 * drifting[-1]["white_noise_k"]


def test_bad_stacks_are_named():
    with pytest.raises(tirpol.Error, match="3-D"):
        calibration.nedt_map(np.zeros((4, 4)), 1.0)
    with pytest.raises(tirpol.Error, match="responsivity_per_k"):
        calibration.nedt_map(np.zeros((4, 3, 5)), np.ones((5, 3)))
