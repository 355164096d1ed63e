// The materials module writes the material files it reads: write → parse gives the same material
// (round trip), whatever the text in its strings, for a constant index and for a spectral table.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

#include "tirpol/core/config.h"
#include "tirpol/core/error.h"
#include "tirpol/core/geometry.h"
#include "tirpol/materials/material.h"
#include "tirpol/materials/microfacet.h"

namespace tirpol::materials {
namespace {

using ::testing::HasSubstr;

MicrofacetMaterialRecord paint(std::vector<double> wavelengths_um, std::vector<double> n,
                               std::vector<double> k) {
    MicrofacetMaterialRecord m;
    m.name = "fitted: \"paint\" #1";  // YAML syntax in the name must survive quoting
    m.source = "tirpol fit of a.csv, b.csv on 2026-11-24T01:00:00Z";
    m.notes = "σ = 0.31 ± 0.02 (2σ); line one\nline two";
    m.comment_lines = {"provenance line", "two lines\nin one entry"};
    m.wavelengths_um = std::move(wavelengths_um);
    m.n = std::move(n);
    m.k = std::move(k);
    // Values with no short decimal form: the writer must keep every bit.
    m.sigma = 0.1 + 0.2;
    m.bias = 2.0 / 3.0;
    m.tau_deg = 17.123456789012345;
    m.omega_deg = 1e6 / 3.0;
    m.rho_d = 1.0 / 7.0 / kPi;
    m.rho_v = 1e-17;
    return m;
}

Material parse(const std::string& text) {
    return material_from_config(ConfigNode::parse(text, "written.yaml"));
}

void expect_same(const MicrofacetMaterialRecord& written, const Material& read) {
    EXPECT_EQ(read.name, written.name);
    EXPECT_EQ(read.source, written.source);
    EXPECT_EQ(read.notes, written.notes);
    const auto* brdf = dynamic_cast<const MicrofacetBrdf*>(read.brdf.get());
    ASSERT_NE(brdf, nullptr);
    for (std::size_t i = 0; i < written.wavelengths_um.size(); ++i) {
        const ShellTargetParameters<double> p = brdf->at(written.wavelengths_um[i]);
        // A table is interpolated even at its nodes (a few ulps); the rest is read back exactly.
        EXPECT_DOUBLE_EQ(p.n, written.n[i]);
        EXPECT_DOUBLE_EQ(p.k, written.k[i]);
        EXPECT_EQ(p.sigma, written.sigma);
        EXPECT_EQ(p.bias, written.bias);
        EXPECT_EQ(p.tau_rad, deg_to_rad(written.tau_deg));
        EXPECT_EQ(p.omega_rad, deg_to_rad(written.omega_deg));
        EXPECT_EQ(p.rho_d, written.rho_d);
        EXPECT_EQ(p.rho_v, written.rho_v);
    }
}

TEST(MaterialWriter, ConstantIndexRoundTripsBitForBit) {
    const MicrofacetMaterialRecord m = paint({10.0}, {1.0 + 1.0 / 3.0}, {0.1 / 3.0});
    const std::string text = microfacet_material_yaml(m);
    EXPECT_THAT(text, HasSubstr("# provenance line\n# two lines\n# in one entry\n"));
    expect_same(m, parse(text));
}

TEST(MaterialWriter, SpectralIndexTableRoundTrips) {
    const MicrofacetMaterialRecord m =
        paint({8.5, 11.0}, {1.55, 1.0 / 3.0 + 1.0}, {0.07, 0.2 / 3.0});
    const std::string text = microfacet_material_yaml(m);
    EXPECT_THAT(text, HasSubstr("wavelength_um: [8.5, 11]"));
    expect_same(m, parse(text));
}

TEST(MaterialWriter, RefusesWhatTheLoaderWouldRefuse) {
    MicrofacetMaterialRecord m = paint({10.0}, {1.5}, {0.1});
    m.sigma = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THAT([&] { microfacet_material_yaml(m); },
                testing::ThrowsMessage<Error>(AllOf(HasSubstr("sigma"), HasSubstr("finite"))));
    m = paint({8.0, 12.0}, {1.5}, {0.1, 0.1});
    EXPECT_THAT([&] { microfacet_material_yaml(m); },
                testing::ThrowsMessage<Error>(HasSubstr("1 n")));
    m = paint({10.0}, {1.5}, {0.1});
    m.name.clear();
    EXPECT_THROW(microfacet_material_yaml(m), Error);
}

}  // namespace
}  // namespace tirpol::materials
