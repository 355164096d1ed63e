// `tirpol brdf`'s library side: directions from zenith/azimuth, the evaluation of a library
// material (reciprocity of its Mueller BRDF) and the JSON and text formats.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_support.h"
#include "tirpol/core/error.h"
#include "tirpol/materials/material.h"

namespace tirpol::materials {
namespace {

using ::testing::HasSubstr;

BrdfEvaluationOptions paint(std::array<double, 2> incident, std::array<double, 2> exitant) {
    BrdfEvaluationOptions o;
    o.material = (test::source_dir() / "config/materials/flat_black_paint.yaml").string();
    o.wavelength_um = 10.0;
    o.incident_deg = incident;
    o.exitant_deg = exitant;
    return o;
}

TEST(BrdfEvaluation, DirectionsAreUnitVectorsFromZenithAndAzimuth) {
    const Vec3 zenith = direction_from_zenith_azimuth_deg(0.0, 123.0);
    EXPECT_NEAR(zenith.z(), 1.0, 1e-15);
    const Vec3 grazing_y = direction_from_zenith_azimuth_deg(90.0, 90.0);
    EXPECT_NEAR(grazing_y.y(), 1.0, 1e-15);
    EXPECT_NEAR(grazing_y.z(), 0.0, 1e-15);
    EXPECT_NEAR(direction_from_zenith_azimuth_deg(37.0, 211.0).norm(), 1.0, 1e-15);
    EXPECT_THROW(direction_from_zenith_azimuth_deg(90.5, 0.0), Error);
    EXPECT_THROW(direction_from_zenith_azimuth_deg(-1.0, 0.0), Error);
    EXPECT_THROW(direction_from_zenith_azimuth_deg(30.0, std::nan("")), Error);
}

// M(wo→wi) = Q M(wi→wo)ᵀ Q, Q = diag(1, 1, −1, 1) (pbrdf.h).
TEST(BrdfEvaluation, LibraryMaterialIsReciprocal) {
    const BrdfEvaluation a = evaluate_brdf(paint({30, 10}, {50, 200}));
    const BrdfEvaluation b = evaluate_brdf(paint({50, 200}, {30, 10}));
    EXPECT_GT(a.mueller_brdf_per_sr(0, 0), 0.0);
    const double q[4] = {1, 1, -1, 1};
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            EXPECT_NEAR(b.mueller_brdf_per_sr(r, c), q[r] * q[c] * a.mueller_brdf_per_sr(c, r),
                        1e-12);
}

TEST(BrdfEvaluation, WavelengthOutsideTheDataRangeNamesTheRange) {
    BrdfEvaluationOptions o = paint({30, 0}, {30, 180});
    o.material = (test::source_dir() / "config/materials/water.yaml").string();  // 6.9–15 µm
    o.wavelength_um = 30.0;
    try {
        evaluate_brdf(o);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("outside the material's data range"));
    }
}

TEST(BrdfEvaluation, JsonAndTextCarryTheMatrixAndParameters) {
    const BrdfEvaluation e = evaluate_brdf(paint({30, 0}, {30, 180}));
    const nlohmann::json j = brdf_evaluation_json(e);
    EXPECT_EQ(j["material"], e.material);
    EXPECT_EQ(j["model"], e.model);
    EXPECT_EQ(j["incident_deg"], nlohmann::json({30.0, 0.0}));
    ASSERT_EQ(j["mueller_brdf_per_sr"].size(), 4u);
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            EXPECT_EQ(j["mueller_brdf_per_sr"][r][c].get<double>(), e.mueller_brdf_per_sr(r, c));
    ASSERT_FALSE(e.parameters.empty());
    EXPECT_EQ(j["parameters"][e.parameters.front().name]["value"].get<double>(),
              e.parameters.front().value);
    const std::string text = brdf_evaluation_text(e);
    EXPECT_THAT(text, HasSubstr(e.material + " (" + e.model + ") at 10 µm"));
    EXPECT_THAT(text, HasSubstr(fmt::format("{:.6e}", e.mueller_brdf_per_sr(0, 0))));
    EXPECT_THAT(text, HasSubstr(" " + e.parameters.front().name + "="));
}

}  // namespace
}  // namespace tirpol::materials
