"""tirpol.report from Python: a measured image that is the simulated one plus Gaussian noise of its
stated σ is "consistent with noise" (z rms ≈ 1, fractions above 2 and 3 near the normal 4.6 % and
0.27 %), a real S1 offset is found with the right size, the statistics dict is report.json, and the
HTML report is written."""

import json

import numpy as np
import pytest

import tirpol
from tirpol import report

H, W, SIGMA = 48, 64, 0.1


def images(s1_offset=0.0, seed=1):
    y, x = np.mgrid[0:H, 0:W]
    simulated = {"S0": (30 + 0.05 * x).astype(np.float32), "S1": np.full((H, W), -0.5, np.float32),
                 "S2": (0.002 * y).astype(np.float32)}
    rng = np.random.default_rng(seed)
    measured = {k: (v + SIGMA * rng.normal(size=(H, W))).astype(np.float32) for k, v in simulated.items()}
    measured["S1"] += np.float32(s1_offset)
    measured.update({f"{k}_std": np.full((H, W), SIGMA, np.float32) for k in ("S0", "S1", "S2")})
    return measured, simulated


def test_noise_of_the_stated_sigma_is_consistent():
    measured, simulated = images()
    stats = report.compare(measured, simulated, registration="none", band_um=(8, 14)).statistics
    region = stats["regions"][0]
    assert region["verdict"] == "consistent with noise"
    for q in ("S0", "S1", "S2"):
        z = region["z"][q]
        assert z["rms"] == pytest.approx(1.0, abs=0.05)
        assert z["fraction_above_2"] == pytest.approx(0.0455, abs=0.015)
        s = region["stats"][q]
        assert abs(s["bias"]) < 4 * s["bias_sigma"]


def test_an_s1_offset_is_measured():
    measured, simulated = images(s1_offset=0.05)
    region = report.compare(measured, simulated, registration="none").statistics["regions"][0]
    assert region["verdicts"]["S1"]["verdict"] == "exceeds noise"
    s1 = region["stats"]["S1"]
    assert s1["bias"] == pytest.approx(0.05, abs=4 * s1["bias_sigma"])
    assert region["verdicts"]["S0"]["verdict"] == "consistent with noise"


def test_html_report_and_json_agree(tmp_path):
    measured, simulated = images()
    comparison = report.compare(tirpol.Image(measured, {"units": "W/(m^2 sr)"}), simulated, registration="none")
    html = comparison.write_html(tmp_path / "report")
    assert html.name == "report.html" and "S1" in html.read_text(encoding="utf-8")
    written = json.loads((tmp_path / "report" / "report.json").read_text(encoding="utf-8"))
    assert written["regions"][0]["stats"] == comparison.statistics["regions"][0]["stats"]


def test_missing_channels_are_named():
    measured, simulated = images()
    del simulated["S2"]
    with pytest.raises(tirpol.Error, match="S2"):
        report.compare(measured, simulated, registration="none")
