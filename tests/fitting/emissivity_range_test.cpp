// Measured emissivities are held to their physical range before any fit (before: one value of
// 1e308 made `fit` crash in Eigen's JacobiSVD through Ceres' covariance; 5 and 1e9 were fitted with
// only a χ² warning). ε_S0 = 1 − DHR lies in [0, 1] and |ε_S1| ≤ 1; measured values may stray by
// the noise tolerance limits::kEmissivityTolerance (0.05), not further.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "error_of.h"
#include "test_support.h"
#include "tirpol/core/error.h"
#include "tirpol/fitting/microfacet_fit.h"

namespace tirpol::fitting {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

std::string error_of(const std::filesystem::path& path) {
    return tirpol::test::error_of([&] { load_emissivity_csv(path); });
}

std::filesystem::path regression(const std::string& name) {
    return tirpol::test::source_dir() / "tests/data/fuzz-regressions/fit_csv" / name;
}

TEST(EmissivityRange, ValuesFarOutsideZeroToOneAreErrorsNamingFileAndLine) {
    EXPECT_THAT(error_of(regression("emissivity_1e308.csv")),
                AllOf(HasSubstr("emissivity_1e308.csv:2"),
                      HasSubstr("eps_s0 = 1e+308 is outside [-0.05, 1.05]")));
    EXPECT_THAT(error_of(regression("emissivity_5.csv")),
                HasSubstr("eps_s0 = 5 is outside [-0.05, 1.05]"));
    tirpol::test::TempDir dir;
    tirpol::test::write_text(dir / "s1.csv",
                             "angle_deg,e_s0,e_s0_sigma,e_s1,e_s1_sigma\n60,0.9,0.01,-1e9,0.01\n");
    EXPECT_THAT(error_of(dir / "s1.csv"),
                HasSubstr("eps_s1 = -1000000000 is outside [-1.05, 1.05]"));
}

TEST(EmissivityRange, NoisyValuesJustOutsideTheRangeAreKept) {
    tirpol::test::TempDir dir;
    tirpol::test::write_text(dir / "noisy.csv",
                             "angle_deg,e_s0,e_s0_sigma,e_s1,e_s1_sigma\n0,1.03,0.02,0.01,0.01\n80,"
                             "-0.02,0.02,-0.9,0.05\n");
    const auto d = load_emissivity_csv(dir / "noisy.csv");
    ASSERT_EQ(d.size(), 1u);
    EXPECT_EQ(d[0].samples.size(), 2u);
}

}  // namespace
}  // namespace tirpol::fitting
