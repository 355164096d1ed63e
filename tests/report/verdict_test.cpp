// Per-quantity verdicts on the z statistic: a pooled fraction over S0, S1, S2 can pass while one
// quantity alone exceeds the noise; an RMS z well below 1 means the stated σ is too large.

#include <gtest/gtest.h>

#include <vector>

#include "tirpol/report/verdict.h"

using namespace tirpol::report;

namespace {
// n values: `above` of them at 2.5 (|z| > 2), the rest at `rest`.
std::vector<float> z_values(std::size_t n, std::size_t above, float rest) {
    std::vector<float> z(n, rest);
    for (std::size_t i = 0; i < above; ++i) z[i] = 2.5f;
    return z;
}
}  // namespace

TEST(ReportVerdict, PooledFractionHidesAQuantityThatAloneExceedsTheNoise) {
    // 1000 pixels per quantity. S0 and S1: 4.5 % beyond 2, RMS ≈ 1.03 → consistent. S2: 7.5 %, above
    // the binomial limit 4.55 % + 3·√(p(1−p)/1000) = 6.53 %. Pooled over 3000 values: 5.5 %, below
    // its limit 4.55 % + 3·√(p(1−p)/3000) = 5.69 % — the pooled verdict would call this consistent.
    const auto z_s0 = z_values(1000, 45, 0.9f), z_s2 = z_values(1000, 75, 0.9f);
    const std::vector<std::uint8_t> mask(1000, 1);
    const ZStats s0 = z_stats(z_s0, mask), s2 = z_stats(z_s2, mask);
    std::vector<float> pooled = z_s0;
    pooled.insert(pooled.end(), z_s0.begin(), z_s0.end());
    pooled.insert(pooled.end(), z_s2.begin(), z_s2.end());
    const ZStats all = z_stats(pooled, std::vector<std::uint8_t>(3000, 1));
    EXPECT_TRUE(consistent_with_noise(all));
    EXPECT_EQ(z_verdict(s0), ZVerdict::Consistent);
    EXPECT_EQ(z_verdict(s2), ZVerdict::ExceedsNoise);
    EXPECT_EQ(worse(worse(z_verdict(s0), z_verdict(s0)), z_verdict(s2)), ZVerdict::ExceedsNoise);
}

TEST(ReportVerdict, RmsFarBelowOneFlagsAnOverestimatedSigma) {
    // z = (m − s)/σ with σ twice the true noise has RMS 0.5 and almost no |z| > 2.
    ZStats z{10000, 0.0001, 0.0, 0.0, 0.5};
    EXPECT_EQ(z_verdict(z), ZVerdict::SigmaOverestimated);
    EXPECT_NE(explain(ZVerdict::SigmaOverestimated, z).find("2.0× too large"), std::string::npos)
        << explain(ZVerdict::SigmaOverestimated, z);
    z.rms = 0.65;  // the 0.3–0.7 band
    EXPECT_EQ(z_verdict(z), ZVerdict::SigmaOverestimated);
    z.rms = 0.95;
    z.fraction_above_2 = 0.04;
    EXPECT_EQ(z_verdict(z), ZVerdict::Consistent);
    // Five pixels with RMS 0.5 are not evidence of anything: the RMS of 5 normal values scatters by 1/√10.
    EXPECT_EQ(z_verdict(ZStats{5, 0.0, 0.0, 0.0, 0.5}), ZVerdict::Consistent);
}

TEST(ReportVerdict, RmsFarAboveOneExceedsTheNoiseEvenWithFewOutliers) {
    // Heavy tails concentrated beyond 3: the |z| > 2 fraction is fine, RMS z = 2 is not.
    EXPECT_EQ(z_verdict(ZStats{10000, 0.04, 0.04, 0.0, 2.0}), ZVerdict::ExceedsNoise);
    EXPECT_EQ(z_verdict(ZStats{}), ZVerdict::NoData);
    EXPECT_EQ(to_string(ZVerdict::ExceedsNoise), "exceeds noise");
}
