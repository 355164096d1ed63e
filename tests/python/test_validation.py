"""Python refuses what the CLI refuses, in Python's words (no command-line flags in messages): the
wrong kind of argument gets a message naming the function and what it expected, not pybind11's
"incompatible function arguments" or "Unable to cast"; NaN in gives NaN out where a value is computed
per element; the C++ libraries' logging (glog, through Ceres) is initialised, so it prints no
"Logging before InitGoogleLogging" warning."""

import subprocess
import sys

import numpy as np
import pytest

import tirpol
from tirpol import calibration, core, simulation


def stokes_image(dolp, shape=(2, 3)):
    s0 = np.full(shape, 2.0, np.float32)
    return tirpol.Image({"S0": s0, "S1": (dolp * s0).astype(np.float32), "S2": np.zeros(shape, np.float32)})


def test_stokes_functions_take_an_image_as_well_as_an_array():
    image = stokes_image(0.25)
    np.testing.assert_allclose(core.dolp(image), np.full((2, 3), 0.25), rtol=1e-6)
    np.testing.assert_allclose(core.aop_deg(image), np.zeros((2, 3)), atol=1e-9)
    assert core.dolp(dict(image)).shape == (2, 3)  # a plain dict of channels too


def test_stokes_functions_say_what_they_expected():
    with pytest.raises(tirpol.Error, match=r"dolp: the image has no channel S1"):
        core.dolp(tirpol.Image({"S0": np.ones((2, 2), np.float32)}))
    with pytest.raises(tirpol.Error, match=r"dolp: got complex values"):
        core.dolp(np.array([1.0 + 1j, 0.1, 0.0, 0.0]))
    with pytest.raises(tirpol.Error, match=r"dop: expected an array of Stokes vectors"):
        core.dop("S0")


def test_nan_in_gives_nan_out():
    dolp = core.dolp(np.array([[1.0, np.nan, 0.0, 0.0], [1.0, 0.5, 0.0, 0.0]]))
    assert np.isnan(dolp[0]) and dolp[1] == pytest.approx(0.5)
    radiance = core.planck_radiance(np.array([np.nan, 10.0]), 300.0)
    assert np.isnan(radiance[0]) and radiance[1] > 0


@pytest.mark.parametrize("wavelength_um", [0.0, -3.0])
def test_planck_refuses_a_wavelength_that_is_not_positive(wavelength_um):
    with pytest.raises(tirpol.Error, match=r"wavelength_um must be > 0"):
        core.planck_radiance(wavelength_um, 300.0)


def test_reduce_names_a_string_key():
    image = np.ones((2, 2), np.float32)
    with pytest.raises(tirpol.Error, match=r"images: key '0' is a str; the keys are analyzer angles"):
        calibration.reduce({"0": image, "45": image, "90": image, "135": image})


def test_reduce_refuses_a_negative_sigma():
    images = {angle: np.ones((2, 2), np.float32) for angle in (0, 45, 90, 135)}
    stds = {angle: np.full((2, 2), 0.1, np.float32) for angle in images}
    stds[90] = np.array([[0.1, 0.1], [-0.2, 0.1]], np.float32)
    with pytest.raises(tirpol.Error, match=r"images\[90\] \(std\): 1 pixel\(s\) are negative \(first at x=0, y=1"):
        calibration.reduce(images, stds)
    stds[90] = np.abs(stds[90])
    assert calibration.reduce(images, stds)["S0_std"].shape == (2, 2)


def test_render_refuses_negative_threads(source_dir):
    scene = simulation.load_scene(str(source_dir / "config/scenes/panels_night.yaml"))
    with pytest.raises(tirpol.Error, match=r"render: threads must be ≥ 0 \(0 uses every core\), got -1"):
        simulation.render(scene, threads=-1)


def test_messages_use_python_names_not_cli_flags():
    for call in (lambda: core.planck_radiance(-1.0, 300.0),
                 lambda: calibration.reduce({"0": np.ones((2, 2), np.float32)})):
        with pytest.raises(tirpol.Error) as caught:
            call()
        assert "--" not in str(caught.value), str(caught.value)


def test_glog_is_initialised_on_import():
    # The same libglog the extension links; uninitialised, its first message carries the warning.
    program = (
        "import ctypes, tirpol\n"
        "glog = ctypes.CDLL('libglog.so.1')\n"
        "initialised = glog._ZN6google26IsGoogleLoggingInitializedEv\n"
        "initialised.restype = ctypes.c_bool\n"
        "print(initialised())\n")
    result = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True, check=True)
    assert result.stdout.strip() == "True", result.stdout + result.stderr
    assert "InitGoogleLogging" not in result.stderr
