"""tirpol.materials from Python: the material library, Kirchhoff's law ε + ∫ρ = 1 checked against an
independent quadrature of the Mueller pBRDF evaluated on arrays of directions, and reciprocity
M(wo→wi) = Q·M(wi→wo)ᵀ·Q with Q = diag(1, 1, −1, 1) (materials/pbrdf.h; tests/materials)."""

import numpy as np
import pytest

import tirpol
from tirpol import core, materials


@pytest.fixture(scope="module")
def library(source_dir):
    return materials.load_library(source_dir / "config" / "materials")


def hemisphere_quadrature(mu_nodes=96, phi_nodes=192):
    """Directions wi over the hemisphere with weights of ∫ f cosθi dωi = ∫∫ f μ dμ dφ (Gauss–Legendre
    in μ = cos θi, uniform in φ)."""
    x, w = np.polynomial.legendre.leggauss(mu_nodes)
    mu, w_mu = 0.5 * (x + 1.0), 0.5 * w
    phi = (np.arange(phi_nodes) + 0.5) * 2 * np.pi / phi_nodes
    m, p = np.meshgrid(mu, phi, indexing="ij")
    s = np.sqrt(1 - m**2)
    wi = np.stack([s * np.cos(p), s * np.sin(p), m], axis=-1)
    weights = (w_mu[:, None] * m) * (2 * np.pi / phi_nodes)
    return wi.reshape(-1, 3), weights.ravel()


def test_library_loads_every_file(library, source_dir):
    files = sorted((source_dir / "config" / "materials").glob("*.yaml"))
    assert len(library) == len(files)
    paint = library["flat_black_paint"]
    assert paint.model == "microfacet" and "Gartley" in paint.source
    assert paint.parameters(10.0)["sigma"][0] == pytest.approx(0.35)


@pytest.mark.parametrize("name", ["flat_black_paint", "concrete"])
@pytest.mark.parametrize("theta_deg", [0.0, 40.0, 70.0])
def test_kirchhoff_emissivity_plus_hemispherical_reflectance_is_one(library, name, theta_deg):
    # Paper eq 5 as Stokes: ε(θo) = e0 − ∫ M(ωi→ωo)·e0 cosθi dωi. The integral here is a plain
    # quadrature of mueller_brdf, independent of the library's importance-sampled one.
    material = library[name]
    t = np.radians(theta_deg)
    wo = np.array([np.sin(t), 0.0, np.cos(t)])
    wi, weights = hemisphere_quadrature()
    m = material.mueller_brdf(wi, np.broadcast_to(wo, wi.shape), 10.0)
    assert m.shape == (wi.shape[0], 4, 4)
    reflected = np.einsum("n,nk->k", weights, m[:, :, 0])
    emissivity = material.emissivity(theta_deg, 10.0)
    assert emissivity.shape == (4,)
    assert emissivity[0] + reflected[0] == pytest.approx(1.0, abs=2e-3)
    assert emissivity[1] == pytest.approx(-reflected[1], abs=2e-3)
    np.testing.assert_allclose(material.reflected_stokes(theta_deg, 10.0), reflected, atol=2e-3)


def test_emissivity_is_polarized_in_the_plane_of_emission_and_smooth_to_grazing(library):
    theta = np.linspace(0.0, 89.5, 180)
    eps = library["flat_black_paint"].emissivity(theta, 10.0)
    assert eps.shape == (180, 4)
    assert np.all(eps[1:, 1] < 0)  # S1 < 0: p-polarized emission (ARCHITECTURE.md)
    assert np.all(eps[:, 0] <= 1) and np.all(eps[:, 0] > 0)
    dolp = core.dolp(eps)
    assert dolp[0] == pytest.approx(0.0, abs=1e-6) and np.all(np.diff(dolp[:-20]) > 0)
    # No salt-and-pepper at grazing angles (the paper's SUV roof): second differences stay small.
    assert np.max(np.abs(np.diff(eps[:, 0], 2))) < 0.01


def test_mueller_brdf_is_reciprocal_and_realizable(library):
    rng = np.random.default_rng(3)

    def directions(n):
        v = rng.normal(size=(n, 3))
        v[:, 2] = np.abs(v[:, 2]) + 0.05
        return v / np.linalg.norm(v, axis=1, keepdims=True)

    wi, wo = directions(200), directions(200)
    q = np.diag([1.0, 1.0, -1.0, 1.0])
    for name in ("flat_black_paint", "concrete", "matte_white_paint"):
        material = library[name]
        forward = material.mueller_brdf(wi, wo, 10.0)
        backward = material.mueller_brdf(wo, wi, 10.0)
        scale = np.abs(forward).max()
        np.testing.assert_allclose(backward, q @ np.transpose(forward, (0, 2, 1)) @ q, atol=1e-9 * scale)
        assert all(core.is_physically_realizable(m, 1e-7) for m in forward[:20])


def test_material_from_dict_and_errors(tmp_path):
    smooth = materials.material_from_dict(
        {"name": "test_glass", "source": "test", "model": "smooth_fresnel", "refractive_index": {"n": 1.5, "k": 0.0}}
    )
    # A smooth dielectric at normal incidence: ε = 1 − ((n − 1)/(n + 1))² = 0.96 (Fresnel).
    assert smooth.emissivity(0.0, 10.0)[0] == pytest.approx(0.96, abs=1e-9)
    with pytest.raises(tirpol.Error, match="refractive_indx"):
        materials.material_from_dict({"name": "x", "source": "test", "model": "smooth_fresnel", "refractive_indx": {"n": 1.5}})
    with pytest.raises(tirpol.Error, match=r"theta_deg: 95 is outside \[0, 90\]"):
        smooth.emissivity(95.0, 10.0)
    with pytest.raises(tirpol.Error, match="shape"):
        smooth.mueller_brdf(np.zeros((3, 2)), np.zeros((3, 2)), 10.0)
