"""tirpol.simulation from Python: the paper's ball-on-snow scene (config/scenes) given as a dict
renders exactly as the YAML file does, obeys Kirchhoff's law in an isothermal enclosure, the day
scene shows the paper's radial polarization on the ball (Gartley et al. §4, Figure 2), and a render
stops on Ctrl-C."""

import copy
import math
import os
import signal
import threading

import numpy as np
import pytest
import yaml

import tirpol
from tirpol import core, simulation


@pytest.fixture(scope="module")
def scenes_dir(source_dir):
    return source_dir / "config" / "scenes"


@pytest.fixture(scope="module")
def ball_on_snow(scenes_dir):
    """The paper's night scene as a plain dict (what a notebook user builds or edits)."""
    with open(scenes_dir / "ball_on_snow_night.yaml", encoding="utf-8") as f:
        return yaml.safe_load(f)


@pytest.fixture(scope="module")
def shared_cache(tmp_path_factory):
    return tmp_path_factory.mktemp("emissivity-cache")


def small(scene, width, height, spp):
    scene.resize(width, height)
    scene.spp = spp
    return scene


def test_replicates_set_the_variance_dof_and_are_checked(ball_on_snow, scenes_dir, shared_cache):
    scene = small(simulation.scene_from_dict(ball_on_snow, base_dir=scenes_dir), 16, 12, 8)
    assert scene.replicates == 2
    scene.replicates = 4
    image = simulation.render(scene, emissivity_cache_dir=shared_cache)
    assert image.attributes["variance_dof"] == 3
    with pytest.raises(Exception, match="replicates"):
        scene.replicates = 0


def test_dict_scene_renders_like_the_yaml_file(ball_on_snow, scenes_dir, shared_cache):
    from_dict = small(simulation.scene_from_dict(ball_on_snow, base_dir=scenes_dir), 40, 32, 2)
    from_file = small(simulation.load_scene(scenes_dir / "ball_on_snow_night.yaml"), 40, 32, 2)
    assert from_dict.object_names == ["snow", "ball", "panel"]
    a = simulation.render(from_dict, emissivity_cache_dir=shared_cache)
    b = simulation.render(from_file, emissivity_cache_dir=shared_cache)
    assert isinstance(a, tirpol.Image) and a.shape == (32, 40)
    for name in ("S0", "S1", "S2", "S3", "S0_var", "S1_var", "S2_var", "depth", "object_id", "temperature_k"):
        assert a[name].dtype == np.float32 and a[name].shape == (32, 40)
        np.testing.assert_array_equal(a[name], b[name])
    assert a.attributes["spp"] == 2 and a.attributes["seed"] == "1"
    # Overrides reach the renderer: another seed, another noise realisation of the same image.
    from_dict.seed = 2
    c = simulation.render(from_dict, emissivity_cache_dir=shared_cache)
    assert c.attributes["seed"] == "2" and not np.array_equal(c["S0"], a["S0"])


def test_isothermal_ball_on_snow_renders_the_blackbody(ball_on_snow, scenes_dir, shared_cache):
    # Kirchhoff (paper eq 5; tests/simulation/isothermal_enclosure_test.cpp): with the sky and every
    # object at 270 K each pixel is L_bb(270 K), unpolarized, within 5σ of its Monte-Carlo error plus
    # 1e-3·L for the emissivity tables (2 % of pixels may exceed it: heavy-tailed grazing weights).
    d = copy.deepcopy(ball_on_snow)
    d["sky"] = {"type": "uniform", "temperature": 270}
    for o in d["objects"]:
        o["temperature"] = 270
    scene = small(simulation.scene_from_dict(d, base_dir=scenes_dir), 48, 40, 24)
    # Per-pixel 5σ tails need per-pixel error bars: 16 replicates (ν = 15), not the default 2
    # (one dof per pixel, meant to be pooled: |t₁| > 5 in 12.6 % of pixels).
    scene.replicates = 16
    image = simulation.render(scene, emissivity_cache_dir=shared_cache)
    l_bb = core.Band(*scene.band_um).radiance(270.0)
    deviation = np.stack([image["S0"] - l_bb, image["S1"], image["S2"]])
    sigma = np.sqrt(np.stack([image["S0_var"], image["S1_var"], image["S2_var"]]))
    outside = np.any(np.abs(deviation) > 5 * sigma + 1e-3 * l_bb, axis=0)
    assert outside.mean() <= 0.02, f"{outside.sum()} of {outside.size} pixels off L_bb = {l_bb}"
    pooled = np.sqrt((sigma.reshape(3, -1) ** 2).sum(axis=1)) / outside.size
    assert np.all(np.abs(deviation.reshape(3, -1).mean(axis=1)) <= 5 * pooled + 1e-3 * l_bb)
    assert np.all(np.abs(image["S3"]) <= 1e-3 * l_bb + 5 * np.sqrt(image["S1_var"] + image["S2_var"]))


def zoom_on_ball(scene_dict, scenes_dir, cache):
    """Renders the scene with the camera zoomed onto the ball; returns the image and a function
    (channel, clock hours) → value at 0.8 of the ball's radius from its centre."""
    scene = simulation.scene_from_dict(scene_dict, base_dir=scenes_dir)
    scene.set_camera({"resolution": [41, 41], "fov_deg": 7, "position": [0, -3.2, 1.1], "look_at": [0, 0, 0.15]})
    scene.spp = 64
    image = simulation.render(scene, emissivity_cache_dir=cache)
    ball = image["object_id"] == scene.object_names.index("ball")
    rows, cols = np.nonzero(ball)
    cy, cx = rows.mean(), cols.mean()
    radius = math.sqrt(ball.sum() / math.pi)
    assert radius > 10, "the ball should fill the view"

    def at(channel, clock_hours):
        a = math.radians(90.0 - 30.0 * clock_hours)  # counter-clockwise from +x; image up = −rows
        y, x = round(cy - 0.8 * radius * math.sin(a)), round(cx + 0.8 * radius * math.cos(a))
        assert ball[y, x]
        return float(image[channel][y, x])

    return image, at


def test_day_ball_emission_is_polarized_radially(scenes_dir, shared_cache):
    # Paper §4, Figure 2 (day, warm ball): S1 extremes at 12/3/6/9 o'clock, S2 at the diagonals; in the
    # camera frame of ARCHITECTURE.md: S1 < 0 at 12 and 6, > 0 at 3 and 9; S2 > 0 at 1:30 and 7:30,
    # < 0 at 10:30 and 4:30.
    with open(scenes_dir / "ball_on_snow_day.yaml", encoding="utf-8") as f:
        day = yaml.safe_load(f)
    _, at = zoom_on_ball(day, scenes_dir, shared_cache)
    for h in (0.0, 6.0):
        assert at("S1", h) < 0, f"S1 at {h} o'clock"
    for h in (3.0, 9.0):
        assert at("S1", h) > 0, f"S1 at {h} o'clock"
    for h in (1.5, 7.5):
        assert at("S2", h) > 0, f"S2 at {h} o'clock"
    for h in (4.5, 10.5):
        assert at("S2", h) < 0, f"S2 at {h} o'clock"


def test_ctrl_c_stops_a_render_and_the_next_one_works(ball_on_snow, scenes_dir, shared_cache):
    scene = simulation.scene_from_dict(ball_on_snow, base_dir=scenes_dir)
    scene.resize(1000, 800)
    scene.spp = 4096  # hours of work: only cancellation ends this call
    timer = threading.Timer(1.0, os.kill, args=(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            simulation.render(scene, emissivity_cache_dir=shared_cache)
    finally:
        timer.cancel()
    small(scene, 8, 8, 1)
    assert simulation.render(scene, emissivity_cache_dir=shared_cache)["S0"].shape == (8, 8)


def test_scene_overrides_are_checked(ball_on_snow, scenes_dir):
    scene = simulation.scene_from_dict(ball_on_snow, base_dir=scenes_dir)
    with pytest.raises(tirpol.Error, match="spp must be ≥ 1"):
        scene.spp = 0
    with pytest.raises(tirpol.Error, match="fov"):
        scene.set_camera({"resolution": [10, 10], "fov_deg": "wide", "position": [0, 0, 1], "look_at": [0, 1, 1]})
