"""The digital twin's renderer-backed camera `sim://<scene.yaml>` from Python: importing tirpol registers
it as the CLI does at start-up (docs/python.md). Without a stage a frame is the rendered scene through the
twin's wire grid at 0° and its detector — twin_sensor() in twin/src/instrument.cpp: τ = 0.7, extinction
ratio 400 (paper §3.1), grid reflectance 0.05 of a 240 K clear night sky, grid emissivity 0.03 at the air
temperature (the scene's 6 °C), gain 800 counts/(W/(m² sr)), offset 3000 counts, NEDT 50 mK at 300 K.
The same render through that model (`simulation.sensor_images`, the linear diattenuator of Chipman, Lam &
Young 2018 eq 6.35 plus the grid's reflection and emission) predicts the frame: its mean within the
detector's noise σ/√N, every pixel within 6σ (σ = gain·NEDT·dL/dT(300 K))."""

import numpy as np

from tirpol import acquisition, core, simulation

WIDTH, HEIGHT, SPP = 64, 48, 4
URI = f"sim://config/scenes/panels_night.yaml?width={WIDTH}&height={HEIGHT}&spp={SPP}"
BAND = core.Band(8.0, 14.0)  # the scene's band
TWIN_SENSOR = {
    "analyzer": {"angles_deg": [0.0], "transmission": 0.7, "extinction_ratio": 400.0},
    "background": {"reflectance": 0.05, "reflected_radiance": float(BAND.radiance(240.0)), "emissivity": 0.03,
                   "temperature": "6 °C"},
    "counts": {"gain_counts_per_radiance": 800.0, "offset_counts": 3000.0, "nedt_k": 0.05,
               "reference_temperature": 300.0},
}


def test_a_scene_camera_frame_is_the_render_through_the_twin_sensor(source_dir):
    camera = acquisition.open_camera(URI)
    assert (camera.info["width"], camera.info["height"]) == (WIDTH, HEIGHT)
    with camera:
        camera.start()
        counts = camera.grab(timeout_s=30.0)["counts"].astype(np.float64)
    assert counts.shape == (HEIGHT, WIDTH)

    # The same render, made here (the renderer is deterministic for a scene and its settings).
    scene = simulation.load_scene(str(source_dir / "config" / "scenes" / "panels_night.yaml"))
    scene.resize(WIDTH, HEIGHT)
    scene.spp = SPP
    stokes = simulation.render(scene)
    [at_0deg] = simulation.sensor_images(stokes, BAND, TWIN_SENSOR)
    counts_model = TWIN_SENSOR["counts"]
    expected = counts_model["gain_counts_per_radiance"] * at_0deg["radiance"].astype(np.float64) + \
        counts_model["offset_counts"]
    sigma = counts_model["gain_counts_per_radiance"] * counts_model["nedt_k"] * BAND.radiance_dT(300.0)

    z = (counts - expected) / sigma
    assert np.max(np.abs(z)) < 6.0
    # The mean of N independent pixels has σ/√N, plus rounding to whole counts (≤ 0.5 counts).
    assert abs(np.mean(counts - expected)) < 5.0 * sigma / np.sqrt(counts.size) + 0.5
    # Not vacuous: the scene's contrast (panels against the sky) is far above the noise.
    assert np.ptp(expected) > 50.0 * sigma
