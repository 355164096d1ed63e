// The sky type registry: every file of simulation/src/skies/ is a sky type by its name, each name
// builds its own sky, a wrong name fails at `type` listing the registered ones, and the per-path
// form the renderer evaluates agrees with the sky's radiance for every type.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "error_of.h"
#include "sky_model.h"
#include "test_support.h"
#include "tirpol/core/config.h"
#include "tirpol/simulation/scene.h"

namespace tirpol::simulation {
namespace {

using ::testing::HasSubstr;

Sky sky_of(const std::string& yaml, const Band& band = Band(8.0, 14.0)) {
    return Sky::from_config(ConfigNode::parse(yaml, "sky.yaml"), band);
}

TEST(SkyRegistry, EveryFileOfTheSkiesFolderIsARegisteredType) {
    std::vector<std::string> files;
    for (const auto& entry :
         std::filesystem::directory_iterator(test::source_dir() / "simulation/src/skies"))
        if (entry.path().extension() == ".cpp") files.push_back(entry.path().stem().string());
    std::sort(files.begin(), files.end());
    ASSERT_FALSE(files.empty());
    EXPECT_EQ(sky_type_names(), files);
}

TEST(SkyRegistry, EachNameBuildsItsOwnSky) {
    // uniform: ε = 1 at its temperature in every direction.
    const Sky uniform = sky_of("{type: uniform, temperature: 250}");
    EXPECT_DOUBLE_EQ(uniform.emissivity(0.3), 1.0);
    EXPECT_DOUBLE_EQ(uniform.temperature_k(0.3), 250.0);
    // clear_sky: ε(zenith) = ε_zenith, at the air temperature.
    const Sky clear = sky_of("{type: clear_sky, air_temperature: 280, zenith_emissivity: 0.7}");
    EXPECT_NEAR(clear.emissivity(1.0), 0.7, 1e-12);
    EXPECT_DOUBLE_EQ(clear.temperature_k(0.2), 280.0);
}

TEST(SkyRegistry, UnknownTypeFailsAtItsLineListingTheRegisteredTypes) {
    const std::string message = test::error_of([] { sky_of("{type: cloudy}"); });
    EXPECT_THAT(message, HasSubstr("sky.yaml:1"));
    EXPECT_THAT(message, HasSubstr("unknown sky type \"cloudy\""));
    EXPECT_THAT(message, HasSubstr("clear_sky, table, uniform"));
}

TEST(SkyRegistry, ThePerPathRadianceOfEveryTypeIsTheSkysRadiance) {
    // Sky::AtWavelength evaluates Planck's law once per wavelength for skies of one temperature
    // and the model's per-path emissivity (the clear sky's exp instead of a pow): equal to
    // rounding to Sky::spectral_radiance, above and below the horizon.
    const Band band(8.0, 14.0);
    const std::vector<Sky> skies = {
        Sky::uniform(250.0), Sky::clear_sky(280.0, 0.7), Sky::clear_sky(280.0, 1.0),
        Sky::table({0.0, 45.0, 90.0},
                   {band.radiance(230.0), band.radiance(250.0), band.radiance(280.0)}, band)};
    for (std::size_t k = 0; k < skies.size(); ++k)
        for (const double wavelength_um : {8.0, 10.5, 14.0}) {
            const Sky::AtWavelength at = skies[k].at_wavelength(wavelength_um);
            for (const double c : {1.0, 0.7, 0.2, 1e-3, 0.0, -0.5}) {
                const Vec3 direction(std::sqrt(std::max(0.0, 1.0 - c * c)), 0.0, c);
                const double expected = skies[k].spectral_radiance(wavelength_um, direction);
                EXPECT_NEAR(at.spectral_radiance(direction), expected, 1e-12 * expected)
                    << "sky " << k << ", λ " << wavelength_um << " µm, cos θ " << c;
            }
        }
}

}  // namespace
}  // namespace tirpol::simulation
