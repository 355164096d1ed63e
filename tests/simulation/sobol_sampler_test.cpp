// The renderer's sampler (sobol_sampler.h): padded Owen-scrambled (0,2)-sequences with independent
// replicates. A (0,m,2)-net in base 2 (Niederreiter, "Random number generation and quasi-Monte
// Carlo methods", SIAM 1992, def. 4.1) puts exactly one of its 2^m points in every elementary
// interval [a/2^k, (a+1)/2^k) × [b/2^(m−k), (b+1)/2^(m−k)); the first 2^m points of the Sobol
// (0,2)-sequence are one, and Owen scrambling keeps it one (Owen 1995). The padding permutation
// must not break it.

#include "sobol_sampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <set>
#include <vector>

namespace tirpol::simulation {
namespace {

/// True if `points` (2^m of them) hold exactly one point in every elementary interval of volume
/// 2^−m.
bool is_02_net(const std::vector<std::array<double, 2>>& points, int m) {
    const std::size_t n = std::size_t{1} << m;
    if (points.size() != n) return false;
    for (int k = 0; k <= m; ++k) {
        std::vector<int> count(n, 0);
        for (const auto& p : points) {
            const auto a =
                static_cast<std::size_t>(p[0] * static_cast<double>(std::size_t{1} << k));
            const auto b =
                static_cast<std::size_t>(p[1] * static_cast<double>(std::size_t{1} << (m - k)));
            ++count[(a << (m - k)) | b];
        }
        for (const int c : count)
            if (c != 1) return false;
    }
    return true;
}

TEST(SobolSampler, UnscrambledPointsAreTheSobolSequence) {
    // The first points of Sobol's first two dimensions (Joe & Kuo's tables; Bratley & Fox 1988):
    // (0, 0), (1/2, 1/2), (1/4, 3/4), (3/4, 1/4), (1/8, 5/8), (5/8, 1/8), (3/8, 3/8), (7/8, 7/8).
    const double expected[8][2] = {{0, 0},         {0.5, 0.5},     {0.25, 0.75},   {0.75, 0.25},
                                   {0.125, 0.625}, {0.625, 0.125}, {0.375, 0.375}, {0.875, 0.875}};
    for (std::uint32_t i = 0; i < 8; ++i) {
        const auto p = sobol_02_point(i);
        EXPECT_EQ(p[0] * 0x1.0p-32, expected[i][0]) << i;
        EXPECT_EQ(p[1] * 0x1.0p-32, expected[i][1]) << i;
    }
}

TEST(SobolSampler, EveryReplicateSlotPairIsA02NetForPowersOfTwo) {
    for (int m = 0; m <= 10; ++m) {
        const std::uint32_t n = 1u << m;
        for (std::uint64_t pixel : {0ull, 1ull, 4711ull})
            for (std::uint32_t replicate : {0u, 5u})
                for (std::uint32_t slot : {0u, 2u, 9u}) {
                    const ReplicateSampler sampler(3, pixel, replicate, n);
                    std::vector<std::array<double, 2>> points;
                    for (std::uint32_t i = 0; i < n; ++i) points.push_back(sampler.pair(i, slot));
                    ASSERT_TRUE(is_02_net(points, m))
                        << "m " << m << " pixel " << pixel << " replicate " << replicate << " slot "
                        << slot;
                }
    }
}

TEST(SobolSampler, OneDimensionalSlotsAreStratifiedAndValuesInUnitInterval) {
    for (std::uint32_t n : {1u, 2u, 7u, 16u, 100u, 256u}) {
        const ReplicateSampler sampler(11, 12345, 3, n);
        // The first n points of the van der Corput sequence hold one or two points in each stratum
        // of width 1/2^⌊log2 n⌋ (exactly one for n = 2^m), and Owen scrambling keeps it so.
        const std::uint32_t strata_count = 1u << (31 - __builtin_clz(n));
        for (std::uint32_t slot : {1u, 3u}) {
            std::vector<int> strata(strata_count, 0);
            for (std::uint32_t i = 0; i < n; ++i) {
                const double u = sampler.single(i, slot);
                ASSERT_GE(u, 0.0);
                ASSERT_LT(u, 1.0);
                ++strata[static_cast<std::size_t>(u * strata_count)];
            }
            const int most = strata_count == n ? 1 : 2;
            for (std::uint32_t j = 0; j < strata_count; ++j) {
                EXPECT_GE(strata[j], 1) << "n " << n << " slot " << slot << " stratum " << j;
                EXPECT_LE(strata[j], most) << "n " << n << " slot " << slot << " stratum " << j;
            }
        }
        for (std::uint32_t i = 0; i < n; ++i)
            for (const double u : sampler.pair(i, 4)) {
                ASSERT_GE(u, 0.0);
                ASSERT_LT(u, 1.0);
            }
    }
}

TEST(SobolSampler, PermutationIsABijectionForAnyLength) {
    for (std::uint32_t n : {1u, 2u, 3u, 5u, 16u, 17u, 100u, 1000u, 4096u})
        for (std::uint64_t key : {0ull, 1ull, 0xDEADBEEFCAFEull}) {
            std::set<std::uint32_t> seen;
            for (std::uint32_t i = 0; i < n; ++i) {
                const std::uint32_t j = permutation_element(i, n, key);
                ASSERT_LT(j, n);
                seen.insert(j);
            }
            EXPECT_EQ(seen.size(), n) << "n " << n << " key " << key;
        }
}

/// Pearson correlation of x and y.
double correlation(const std::vector<double>& x, const std::vector<double>& y) {
    const double n = static_cast<double>(x.size());
    const double mx = std::accumulate(x.begin(), x.end(), 0.0) / n,
                 my = std::accumulate(y.begin(), y.end(), 0.0) / n;
    double sxy = 0.0, sxx = 0.0, syy = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        sxy += (x[i] - mx) * (y[i] - my);
        sxx += (x[i] - mx) * (x[i] - mx);
        syy += (y[i] - my) * (y[i] - my);
    }
    return sxy / std::sqrt(sxx * syy);
}

// Independence is what makes the mean unbiased and the replicate variance exact: values of the same
// sample index in different slots, replicates or pixels must be uncorrelated, and each value
// uniform. Pooled over 2000 replicates of 16 points (32 000 pairs) an independent pair's
// correlation has a standard deviation of 1/√32000 = 0.0056; 0.03 is 5.4 of them.
TEST(SobolSampler, SlotsReplicatesAndPixelsAreDecorrelated) {
    constexpr std::uint32_t kPoints = 16;
    std::vector<double> slot0, slot2, slot3, next_replicate, next_pixel;
    std::vector<int> histogram(16, 0);
    for (std::uint32_t r = 0; r < 2000; ++r) {
        const ReplicateSampler a(1, 77, r, kPoints), b(1, 77, r + 5000, kPoints),
            c(1, 78, r, kPoints);
        for (std::uint32_t i = 0; i < kPoints; ++i) {
            slot0.push_back(a.pair(i, 0)[0]);
            slot2.push_back(a.pair(i, 2)[1]);
            slot3.push_back(a.single(i, 3));
            next_replicate.push_back(b.pair(i, 0)[0]);
            next_pixel.push_back(c.pair(i, 0)[0]);
        }
        ++histogram[static_cast<std::size_t>(a.pair(0, 0)[1] * 16.0)];  // one point's distribution
    }
    EXPECT_LT(std::abs(correlation(slot0, slot2)), 0.03);
    EXPECT_LT(std::abs(correlation(slot0, slot3)), 0.03);
    EXPECT_LT(std::abs(correlation(slot2, slot3)), 0.03);
    EXPECT_LT(std::abs(correlation(slot0, next_replicate)), 0.03);
    EXPECT_LT(std::abs(correlation(slot0, next_pixel)), 0.03);
    // The first point of 2000 replicates in 16 bins: χ² with 15 dof; P(χ²₁₅ > 40) = 4e-4.
    double chi2 = 0.0;
    for (const int h : histogram) chi2 += std::pow(h - 125.0, 2) / 125.0;
    EXPECT_LT(chi2, 40.0);
}

TEST(SobolSampler, PathSamplerFallsBackToTheStreamPastTheScrambledBounces) {
    const ReplicateSampler replicate(1, 2, 3, 8);
    SampleStream reference(1, 2, 3);
    PathSampler path(replicate, 5, 1, 2, 3);  // its stream is SampleStream(1, 2, 3)
    EXPECT_EQ(path.scatter(0), replicate.pair(5, 2));
    EXPECT_EQ(path.roulette(kSobolBounces - 1), replicate.single(5, 2 + 2 * kSobolBounces - 1));
    const auto deep = path.scatter(kSobolBounces);
    EXPECT_EQ(deep[0], reference.next());
    EXPECT_EQ(deep[1], reference.next());
}

}  // namespace
}  // namespace tirpol::simulation
