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


# Regions, control points and a camera model, as `tirpol compare --rois --control-points --camera`.

PANEL = [[10, 10], [30, 10], [30, 30], [10, 30]]
OTHER = [[40, 10], [60, 10], [60, 40], [40, 40]]


def test_regions_as_numpy_polygons_find_the_offset_region_only():
    measured, simulated = images()
    measured["S1"][10:31, 10:31] += np.float32(0.1)  # the panel's pixels (edges included)
    stats = report.compare(measured, simulated, registration="none",
                           regions={"panel": np.array(PANEL, float), "other": np.array(OTHER)}).statistics
    by_name = {r["name"]: r for r in stats["regions"]}
    assert set(by_name) == {"panel", "other"}
    assert by_name["panel"]["pixel_count"] == 21 * 21
    assert by_name["panel"]["verdicts"]["S1"]["verdict"] == "exceeds noise"
    assert by_name["panel"]["stats"]["S1"]["bias"] == pytest.approx(0.1, abs=0.02)
    assert by_name["other"]["verdict"] == "consistent with noise"


def test_regions_from_a_list_a_yaml_file_and_a_dict_agree(tmp_path):
    measured, simulated = images(s1_offset=0.02)
    (tmp_path / "rois.yaml").write_text(
        "background: other\nregions:\n  - name: panel\n    polygon: %s\n  - name: other\n    polygon: %s\n"
        % (PANEL, OTHER), encoding="utf-8")
    as_list = [{"name": "panel", "polygon": PANEL}, {"name": "other", "polygon": OTHER}]
    results = [
        report.compare(measured, simulated, registration="none", regions=tmp_path / "rois.yaml"),
        report.compare(measured, simulated, registration="none", regions=str(tmp_path / "rois.yaml")),
        report.compare(measured, simulated, registration="none", regions=as_list, background="other"),
        report.compare(measured, simulated, registration="none",
                       regions={"regions": as_list, "background": "other"}),
    ]
    stats = [r.statistics for r in results]
    for s in stats[1:]:
        assert s["regions"] == stats[0]["regions"]
    assert stats[0]["background"] == "other"
    assert stats[0]["regions"][0]["s1_contrast"] is not None
    # A file is recorded in the provenance with its checksum.
    assert stats[0]["provenance"]["inputs"][0]["role"] == "regions"


@pytest.mark.parametrize("regions, error, message", [
    ({"panel": [[1, 2], [3, 4]]}, tirpol.Error, "at least 3 vertices"),
    ({"panel": [1, 2, 3]}, ValueError, r"regions\['panel'\] polygon: expected an \(n, 2\) array"),
    ({"panel": [[1, 2], [3, float("nan")], [5, 6]]}, ValueError, "finite"),
    ({"panel": [[0, 0], [100, 0], [100, 10]]}, tirpol.Error, "panel.*outside the 64×48"),
    ([{"name": "a", "polygon": PANEL}, {"name": "a", "polygon": OTHER}], tirpol.Error, "duplicate region name 'a'"),
    ([{"name": "a", "polygon": PANEL, "colour": "red"}], ValueError, r"regions\[0\]: expected a dict with 'name' and 'polygon'"),
    ({"regions": [{"name": "a", "polygon": PANEL}], "backgruond": "a"}, ValueError, "unknown key 'backgruond'"),
    ({"regions": [{"name": "a", "polygon": PANEL}], "background": "b"}, tirpol.Error, "'b' names no region"),
    (42, ValueError, "regions: expected a regions YAML path"),
])
def test_bad_regions_are_named(regions, error, message):
    measured, simulated = images()
    with pytest.raises(error, match=message):
        report.compare(measured, simulated, registration="none", regions=regions)


def shifted(image, dx):
    """The image moved dx pixels to the right (content at column x goes to x + dx), edges repeated."""
    return {k: np.concatenate([np.repeat(v[:, :1], dx, axis=1), v[:, :-dx]], axis=1) for k, v in image.items()}


def textured_pair(dx):
    rng = np.random.default_rng(4)
    y, x = np.mgrid[0:H, 0:W]
    s0 = 30 + 3 * np.sin(x / 3.0) * np.cos(y / 4.0) + 0.2 * rng.normal(size=(H, W))
    simulated = {"S0": s0.astype(np.float32), "S1": np.full((H, W), -0.5, np.float32),
                 "S2": np.zeros((H, W), np.float32)}
    return shifted(simulated, dx), simulated


def test_control_points_register_a_known_shift():
    measured, simulated = textured_pair(dx=3)
    # The measured pixel (x, y) shows the simulated pixel (x - 3, y).
    m = np.array([[10, 10], [50, 10], [50, 40], [10, 40], [30, 25]], float)
    s = m - [3, 0]
    as_rows = report.compare(measured, simulated, control_points=np.hstack([m, s])).statistics
    as_pair = report.compare(measured, simulated, control_points=(m, s)).statistics
    g = as_rows["registration"]
    assert g["method"] == "control-points"
    assert g["control_point_rms_px"] < 1e-6
    assert g["measured_to_simulated"][2] == pytest.approx(-3.0, abs=1e-6)
    assert as_pair["registration"]["measured_to_simulated"] == pytest.approx(g["measured_to_simulated"])
    with pytest.raises(ValueError, match="at least 4 pairs, got 3"):
        report.compare(measured, simulated, control_points=np.hstack([m, s])[:3])
    with pytest.raises(ValueError, match=r"control_points: expected an \(n, 4\) array"):
        report.compare(measured, simulated, control_points=np.zeros((5, 3)))
    with pytest.raises(ValueError, match="'control-points' needs control_points"):
        report.compare(measured, simulated, registration="control-points")


CAMERA_YAML = """%YAML:1.0
---
image_width: 64
image_height: 48
camera_matrix: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 80., 0., 31.5, 0., 80., 23.5, 0., 0., 1. ]
distortion_coefficients: !!opencv-matrix
   rows: 1
   cols: 5
   dt: d
   data: [ -0.1, 0.01, 0., 0., 0. ]
"""


def test_a_camera_model_registers_by_the_model(tmp_path):
    camera = tmp_path / "camera.yaml"
    camera.write_text(CAMERA_YAML, encoding="utf-8")
    measured, simulated = images()
    rendered = tirpol.Image(simulated, {"camera_intrinsics_px": [80.0, 80.0, 31.5, 23.5],
                                        "camera_distortion": [-0.1, 0.01, 0.0, 0.0, 0.0]})
    stats = report.compare(measured, rendered, camera_model=camera, regions={"panel": PANEL}).statistics
    assert stats["registration"]["method"] == "camera-model"
    assert stats["registration"]["model"] == "identity"
    assert stats["regions"][0]["verdict"] == "consistent with noise"
    assert [i["role"] for i in stats["provenance"]["inputs"]] == ["camera model"]
    # Rendered through another lens: refused, naming the field.
    other = tirpol.Image(simulated, {"camera_intrinsics_px": [90.0, 90.0, 31.5, 23.5],
                                     "camera_distortion": [-0.1, 0.01, 0.0, 0.0, 0.0]})
    with pytest.raises(tirpol.Error, match=r"rendered with intrinsics fx fy cx cy \[90, 90"):
        report.compare(measured, other, camera_model=camera)
    with pytest.raises(ValueError, match="a camera model registers by the model"):
        report.compare(measured, rendered, camera_model=camera, registration="auto")


@pytest.mark.parametrize("argument, value, message", [
    ("gain_sigma", -0.1, r"gain_sigma: expected a relative gain uncertainty in \[0, 1\)"),
    ("offset_sigma", float("nan"), "offset_sigma: expected a non-negative radiance"),
    ("false_alarm", 0.7, r"false_alarm: expected a probability in \(0, 0.5\)"),
    ("power", 0.3, r"power: expected a probability in \(0.5, 1\)"),
    ("measured_frame_sigma", -1.0, "measured_frame_sigma: expected a positive radiance"),
    ("band_um", (14.0, 8.0), "band_um: expected"),
    ("registration", "ecc", "registration: .*expected one of none, auto"),
])
def test_bad_options_are_named_as_python_spells_them(argument, value, message):
    measured, simulated = images()
    with pytest.raises(ValueError, match=message):
        report.compare(measured, simulated, **{argument: value})


def test_options_reach_the_design():
    measured, simulated = images()
    stats = report.compare(measured, simulated, registration="none", false_alarm=0.01, power=0.9,
                           gain_sigma=0.005).statistics
    assert stats["design"]["false_alarm_per_region"] == 0.01
    assert stats["design"]["power"] == 0.9
    assert "gain 0.5 %" in stats["sigma_contains"]["measured"]
