"""tirpol.core from Python: the same physical laws as tests/core (Planck, Malus, Stokes conventions,
Mueller realizability) and the EXR round trip numpy → EXR → numpy."""

import math

import numpy as np
import pytest

import tirpol
from tirpol import core

# CODATA 2018 (Tiesinga et al., Rev. Mod. Phys. 93, 025010, 2021): Stefan–Boltzmann constant and
# Wien's wavelength displacement constant, as in tests/core/radiometry_test.cpp.
STEFAN_BOLTZMANN = 5.670374419e-8  # W m⁻² K⁻⁴
WIEN_B_UM_K = 2897.771955


def test_planck_total_radiance_is_stefan_boltzmann_over_pi():
    band = core.Band(0.2, 1000.0)  # 1000 µm: the longest wavelength a Band accepts
    c, h, k, lam = 299792458.0, 6.62607015e-34, 1.380649e-23, 1000e-6
    for t in (250.0, 300.0, 1000.0):
        # The tail beyond 1000 µm from the series of Planck's law in x = hc/(λkT) (as the C++ test):
        # ∫_Λ^∞ L dλ = 2ckT/(3Λ³) − hc²/(4Λ⁴) + h²c³/(30kTΛ⁵).
        tail = 2 * c * k * t / (3 * lam**3) - h * c * c / (4 * lam**4) + h * h * c**3 / (30 * k * t * lam**5)
        assert (band.radiance(t) + tail) / (STEFAN_BOLTZMANN * t**4 / math.pi) == pytest.approx(1.0, abs=2e-8)


def test_planck_peak_follows_wiens_law_on_arrays():
    wavelength_um = np.linspace(5.0, 15.0, 100001)
    for t in (250.0, 300.0):
        radiance = core.planck_radiance(wavelength_um, t)  # broadcasting array × scalar
        assert radiance.shape == wavelength_um.shape
        assert wavelength_um[np.argmax(radiance)] * t == pytest.approx(WIEN_B_UM_K, abs=0.05)


def test_brightness_temperature_inverts_band_radiance_on_an_image():
    band = core.Band(8.0, 14.0)
    temperature_k = np.linspace(200.0, 400.0, 640 * 4).reshape(40, 64)
    radiance = band.radiance(temperature_k)
    assert radiance.shape == (40, 64)
    assert np.all(np.diff(radiance.ravel()) > 0)  # monotonic in T
    np.testing.assert_allclose(band.brightness_temperature(radiance), temperature_k, rtol=0, atol=1e-3)
    assert math.isnan(band.brightness_temperature(-1.0))
    assert band.radiance_dT(300.0) == pytest.approx((band.radiance(300.01) - band.radiance(299.99)) / 0.02, rel=1e-6)


def test_band_with_triangular_response_integrates_it_exactly():
    # A triangle 8–10–12 µm with peak 1 has area ½·4·1 = 2 µm (tests/core/radiometry_test.cpp).
    band = core.Band(7.0, 13.0, rsr_wavelength_um=[8, 10, 12], rsr_response=[0, 1, 0])
    assert band.effective_width_um == pytest.approx(2.0, abs=1e-12)


def test_polarizers_follow_malus_law_and_the_stokes_convention():
    unpolarized = np.array([1.0, 0.0, 0.0, 0.0])
    horizontal = core.linear_polarizer(0.0) @ unpolarized
    np.testing.assert_allclose(horizontal, [0.5, 0.5, 0, 0], atol=1e-15)  # S1 > 0 along 0°
    np.testing.assert_allclose(core.linear_polarizer(45.0) @ unpolarized, [0.5, 0, 0.5, 0], atol=1e-15)
    for theta in np.linspace(0, 180, 13):
        transmitted = core.linear_polarizer(theta) @ horizontal
        assert transmitted[0] == pytest.approx(0.5 * math.cos(math.radians(theta)) ** 2, abs=1e-15)
    # A quarter-wave plate at 45° turns horizontal light circular; its Mueller matrix is the one of
    # the Jones matrix diag(1, −i) rotated by 45° (tests/core/polarization_test.cpp pins the same pair).
    circular = core.linear_retarder(45.0, 90.0) @ np.array([1.0, 1.0, 0, 0])
    np.testing.assert_allclose(np.abs(circular), [1, 0, 0, 1], atol=1e-12)
    c = math.sqrt(0.5)
    rotation = np.array([[c, c], [-c, c]])
    jones_qwp_45 = rotation.T @ np.diag([1, -1j]) @ rotation
    np.testing.assert_allclose(core.mueller_from_jones(jones_qwp_45), core.linear_retarder(45.0, 90.0), atol=1e-14)


def test_jones_and_mueller_agree_and_realizability_is_checked():
    jones_polarizer = np.array([[1, 0], [0, 0]], dtype=complex)
    np.testing.assert_allclose(core.mueller_from_jones(jones_polarizer), core.linear_polarizer(0.0), atol=1e-15)
    assert core.is_physically_realizable(core.polarizer_with_extinction(30.0, 0.9, 400.0))
    # diag(1, 1, 1, −1) has a negative Cloude eigenvalue (−½): not a physical element.
    assert not core.is_physically_realizable(np.diag([1.0, 1.0, 1.0, -1.0]))
    rotated = core.rotate_element(core.linear_polarizer(0.0), 30.0)
    np.testing.assert_allclose(rotated, core.linear_polarizer(30.0), atol=1e-15)


def test_stokes_helpers_work_on_images_of_stokes_vectors():
    s = np.stack([core.linearly_polarized(2.0, 0.3, aop) for aop in (0.0, 30.0, 150.0)]).reshape(1, 3, 4)
    np.testing.assert_allclose(core.dolp(s), [[0.3, 0.3, 0.3]], atol=1e-12)
    np.testing.assert_allclose(core.aop_deg(s), [[0.0, 30.0, 150.0]], atol=1e-9)
    assert core.dolp(s[..., :3]).shape == (1, 3)  # linear Stokes (..., 3) accepted
    assert core.is_realizable(s).all()
    assert not core.is_realizable(np.array([1.0, 0.9, 0.9, 0.0]))
    with pytest.raises(tirpol.Error, match=r"shape \(\.\.\., 4\)"):
        core.dolp(np.zeros((4, 5)))


def test_exr_round_trip_is_exact(tmp_path):
    rng = np.random.default_rng(7)
    channels = {name: rng.normal(size=(37, 53)).astype(np.float32) for name in ("S0", "S1", "S2", "S3")}
    channels["S0"][0, :3] = [np.nan, np.inf, -np.inf]
    channels["S1"][5, 5] = np.finfo(np.float32).tiny  # a denormal-edge value survives too
    attributes = {"units": "W/(m^2 sr)", "spp": 16, "exposure_time_us": 12.5, "band_um": [8.0, 14.0]}
    path = tmp_path / "round_trip.exr"
    core.write_exr(path, channels, attributes)
    image = core.read_exr(path)
    assert isinstance(image, tirpol.Image)
    assert list(image) == ["S0", "S1", "S2", "S3"]  # channel order kept
    for name, array in channels.items():
        assert image[name].dtype == np.float32 and image[name].shape == (37, 53)
        np.testing.assert_array_equal(image[name], array)  # bit-exact, NaN and ±inf included
    for key, value in attributes.items():
        assert image.attributes[key] == value
    # An Image carries its attributes through a second write.
    core.write_exr(tmp_path / "again.exr", image)
    assert core.read_exr(tmp_path / "again.exr").attributes["band_um"] == [8.0, 14.0]


def test_nan_stokes_give_nan_degree_and_angle_not_unpolarized():
    # A dead pixel (NaN) must stay visibly missing: DoLP 0 would read as "unpolarized".
    nan = float("nan")
    assert math.isnan(core.dolp(np.array([nan] * 4)))
    assert math.isnan(core.dop(np.array([nan] * 4)))
    assert math.isnan(core.aop_deg(np.array([nan] * 4)))
    assert math.isnan(core.dolp(np.array([1.0, nan, 0.0, 0.0])))
    # Finite pixels next to it keep their values (Malus: S1 = 0.5 S0 → DoLP 0.5, AoP 0°).
    both = core.dolp(np.array([[nan, 0.0, 0.0, 0.0], [2.0, 1.0, 0.0, 0.0]]))
    assert math.isnan(both[0]) and both[1] == pytest.approx(0.5)


def test_write_exr_refuses_a_channel_name_it_cannot_store(tmp_path):
    plane = np.zeros((2, 3), np.float32)
    # OpenEXR names are NUL-terminated: "S0\0x" would be stored as "S0" (colliding with a real S0).
    with pytest.raises(tirpol.Error, match="NUL"):
        core.write_exr(tmp_path / "nul.exr", {"S0": plane, "S0\0x": plane})
    # Invalid UTF-8 reaches Python as bytes or as a str with a lone surrogate (surrogateescape).
    with pytest.raises(tirpol.Error, match="not valid UTF-8"):
        core.write_exr(tmp_path / "latin1.exr", {b"temp\xe9rature".decode("utf-8", "surrogateescape"): plane})
    with pytest.raises(tirpol.Error, match="channel names must be str, got bytes"):
        core.write_exr(tmp_path / "bytes.exr", {b"S0": plane})
    assert not list(tmp_path.iterdir())  # nothing written, no temp file left
