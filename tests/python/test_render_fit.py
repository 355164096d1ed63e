"""tirpol.fitting.fit_through_renderer from Python: a render of ball_on_snow_night with its own seed is
the measurement (σ = the render's own √S*_var), and the glossy paint's index n is fitted back through
the renderer from a wrong start. The truth must lie within 3σ of the estimate (a 1-parameter fit at
48×40 pixels and 4 samples per pixel: σ(n) ≈ 0.03), and bad views are errors naming the key."""

import numpy as np
import pytest

import tirpol
from tirpol import fitting, simulation


@pytest.fixture(scope="module")
def scene_and_measurement(source_dir):
    scene = simulation.load_scene(source_dir / "config" / "scenes" / "ball_on_snow_night.yaml")
    scene.resize(48, 40)
    scene.spp = 4
    scene.seed = 3
    rendered = simulation.render(scene, emissivity_cache_dir="")
    measured = {k: rendered[k] for k in ("S0", "S1", "S2")}
    measured.update({k + "_std": np.sqrt(rendered[k + "_var"]) for k in ("S0", "S1", "S2")})
    return scene, measured


def test_the_glossy_paint_index_comes_back(scene_and_measurement):
    scene, measured = scene_and_measurement
    result = fitting.fit_through_renderer(
        scene, [{"measured": measured, "objects": ["ball", "panel"]}],
        [{"material": "glossy_black_paint", "name": "n", "lower": 1.2, "upper": 2.5, "initial": 1.4}], seed=11)
    assert result["usable"], result["report"]
    (n,) = result["parameters"]
    assert n["name"] == "n" and n["material"] == "glossy_black_paint"
    assert abs(n["value"] - 1.55) < 3 * n["sigma"], result["report"]
    assert result["covariance"].shape == (1, 1)
    assert np.isclose(np.sqrt(result["covariance"][0, 0]), n["sigma"])
    assert result["dof"] == 2 * 3 - 1 and result["renders"] > 3


def test_bad_views_name_the_key(scene_and_measurement):
    scene, measured = scene_and_measurement
    parameter = [{"material": "glossy_black_paint", "name": "n", "lower": 1.2, "upper": 2.5}]
    with pytest.raises(tirpol.Error, match=r"views\[0\]: unknown key 'mask'"):
        fitting.fit_through_renderer(scene, [{"measured": measured, "mask": None}], parameter)
    with pytest.raises(tirpol.Error, match="no object named 'sled'"):
        fitting.fit_through_renderer(scene, [{"measured": measured, "objects": ["sled"]}], parameter)
    with pytest.raises(tirpol.Error, match=r"regions\['top'\]: expected a boolean mask of shape \(40, 48\)"):
        fitting.fit_through_renderer(scene, [{"measured": measured, "regions": {"top": np.ones((4, 4), bool)}}],
                                     parameter)
