// Material files: every file of the library loads and obeys the physical invariants; bad files give
// errors naming file, line and field.

#include "tirpol/materials/material.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.h"
#include "tirpol/core/config.h"
#include "tirpol/core/error.h"
#include "tirpol/core/stokes.h"
#include "tirpol/materials/emissivity.h"

namespace tirpol::materials {
namespace {

using ::testing::HasSubstr;

std::vector<std::string> library_files() {
    std::vector<std::string> out;
    for (const auto& e :
         std::filesystem::directory_iterator(test::source_dir() / "config/materials"))
        if (e.path().extension() == ".yaml") out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
}

class LibraryMaterial : public ::testing::TestWithParam<std::string> {};

// For every library material, over its data range: 0 ≤ ε_S0 ≤ 1, |ε_S1| ≤ ε_S0, ε_S1 ≤ 0 (emission
// polarized in the plane of emission), DHR ≤ 1 up to 89.9°, realizable Mueller matrices, and a
// literature source in the file.
TEST_P(LibraryMaterial, LoadsAndObeysInvariants) {
    const Material m = load_material(test::source_dir() / "config/materials" / GetParam());
    EXPECT_FALSE(m.name.empty());
    EXPECT_GT(m.source.size(), 40u) << "cite the literature source";
    ASSERT_TRUE(m.brdf);
    const auto [lo, hi] = m.brdf->valid_wavelength_range_um();
    const double wl_lo = std::max(lo, 8.0), wl_hi = std::min(hi, 14.0);
    EmissivityOptions coarse;
    coarse.radial_panels = 6;
    coarse.azimuth_panels = 4;
    for (double wl : {wl_lo, 0.5 * (wl_lo + wl_hi), wl_hi})
        for (double deg : {0.0, 30.0, 60.0, 80.0, 89.9}) {
            const StokesVector e =
                directional_emissivity(*m.brdf, std::cos(deg_to_rad(deg)), wl, coarse);
            EXPECT_GE(e(0), -1e-9) << wl << " µm " << deg << "°";
            EXPECT_LE(e(0), 1.0 + 1e-9);
            EXPECT_LE(std::abs(e(1)), e(0) + 1e-9);
            EXPECT_LE(e(1), 1e-9);
            EXPECT_NEAR(e(2), 0.0, 1e-9);
        }
    const Vec3 wi = Vec3(0.3, 0.4, 0.8).normalized(), wo = Vec3(-0.5, 0.1, 0.6).normalized();
    EXPECT_TRUE(is_physically_realizable(m.brdf->eval(wi, wo, 10.0)));
}

INSTANTIATE_TEST_SUITE_P(ConfigMaterials, LibraryMaterial, ::testing::ValuesIn(library_files()),
                         [](const ::testing::TestParamInfo<std::string>& param_info) {
                             std::string n = param_info.param.substr(0, param_info.param.find('.'));
                             for (char& c : n)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return n;
                         });

TEST(MaterialLibrary, LoadsDirectoryAndListsNamesOnUnknown) {
    const auto lib = MaterialLibrary::load_directory(test::source_dir() / "config/materials");
    EXPECT_GE(lib.names().size(), 16u);
    EXPECT_EQ(lib.get("flat_black_paint").brdf->model(), "microfacet");
    try {
        lib.get("flat_blak_paint");
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("did you mean \"flat_black_paint\""));
        EXPECT_THAT(e.what(), HasSubstr("water"));
    }
}

TEST(MaterialFile, ErrorsNameFileLineAndField) {
    test::TempDir dir;
    test::write_text(dir / "typo.yaml",
                     "name: x\nsource: s\nmodel: microfacet\nrefractive_index: {n: 1.5, k: 0}\n"
                     "parameters:\n  sigma: 0.2\n  rho_dd: 0.1\n");
    try {
        load_material(dir / "typo.yaml");
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("typo.yaml:"));
        EXPECT_THAT(e.what(), HasSubstr("rho_dd"));
    }
    test::write_text(dir / "range.yaml",
                     "name: x\nsource: s\nmodel: microfacet\nrefractive_index: {n: 1.5, k: 0}\n"
                     "parameters: {sigma: -1}\n");
    try {
        load_material(dir / "range.yaml");
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("range.yaml:5"));
        EXPECT_THAT(e.what(), HasSubstr("sigma"));
    }
    test::write_text(dir / "model.yaml", "name: x\nsource: s\nmodel: phong\n");
    EXPECT_THROW(load_material(dir / "model.yaml"), Error);
    // Energy: a diffuse term that with the specular lobe reflects more than it receives is refused.
    test::write_text(dir / "energy.yaml",
                     "name: x\nsource: s\nmodel: microfacet\nrefractive_index: {n: 30, k: 90}\n"
                     "parameters: {sigma: 0.2, rho_d: 0.2}\n");
    try {
        load_material(dir / "energy.yaml");
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("reflect more than they receive"));
    }
}

// Scenes define materials inline: the same loader works on an in-memory mapping, with spectral
// parameters written as {wavelength_um, value} tables.
TEST(MaterialFile, InlineDefinitionWithSpectralParameter) {
    const ConfigNode node = ConfigNode::parse(
        "material:\n  name: inline_paint\n  source: test\n  model: microfacet\n"
        "  refractive_index: {wavelength_um: [8, 12], n: [1.5, 1.7], k: [0.05, 0.1]}\n"
        "  parameters:\n    sigma: {wavelength_um: [8, 12], value: [0.2, 0.4]}\n",
        "scene.yaml");
    const Material m = material_from_config(node.at("material"));
    EXPECT_EQ(m.name, "inline_paint");
    const auto params = m.brdf->parameters(10.0);
    EXPECT_NEAR(params[0].value, 1.6, 1e-12);
    EXPECT_NEAR(params[2].value, 0.3, 1e-12);
    EXPECT_EQ(m.brdf->valid_wavelength_range_um(), std::make_pair(8.0, 12.0));
}

// The old optional `thermal:` map was parsed and never read; a file that still has it is told where
// thermal properties go instead of having them silently ignored.
TEST(MaterialFile, ThermalMapIsRefusedWithWhereItBelongs) {
    const ConfigNode node = ConfigNode::parse(
        "name: paint\nsource: test\nmodel: lambertian\nreflectance: 0.1\nthermal: "
        "{conductivity_w_m_k: 0.2}\n",
        "old_paint.yaml");
    try {
        material_from_config(node);
        FAIL() << "a material with `thermal:` was accepted";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("old_paint.yaml"));
        EXPECT_THAT(e.what(), HasSubstr("thermal_materials"));
    }
}

}  // namespace
}  // namespace tirpol::materials
