// The renderer's sampler (sobol_sampler.h): an Owen-scrambled Sobol prefix and padded
// Owen-scrambled (0,2)-sequences, with independent replicates. A (t,m,s)-net in base 2
// (Niederreiter, "Random number generation and quasi-Monte Carlo methods", SIAM 1992, def. 4.1)
// puts exactly 2^t of its 2^m points in every elementary interval ∏ [a_j/2^k_j, (a_j+1)/2^k_j) with
// Σ k_j = m − t. The first 2^m points of s Sobol dimensions are one with t = Σ (deg p_j − 1) over
// their primitive polynomials (Sobol 1967; Joe & Kuo 2008 §2), Owen scrambling keeps nets nets
// (Owen 1995), and the sample-index permutations must not break it.

#include "sobol_sampler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numeric>
#include <set>
#include <string>
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

/// True if `points` (2^m of them, each of s coordinates) are a (t,m,s)-net in base 2: every
/// elementary interval of volume 2^(t−m) holds exactly 2^t of them.
bool is_net(const std::vector<std::vector<double>>& points, int m, int t) {
    if (points.size() != std::size_t{1} << m || t > m) return false;
    const std::size_t s = points.front().size();
    std::vector<int> k(s, 0);  // the interval's side 2^−k_j along coordinate j
    // Every composition of m − t into s parts k_j ≥ 0.
    const std::function<bool(std::size_t, int)> compositions = [&](std::size_t j, int left) {
        if (j + 1 == s) {
            k[j] = left;
            std::vector<int> count(std::size_t{1} << (m - t), 0);
            for (const auto& p : points) {
                std::size_t box = 0;
                for (std::size_t c = 0; c < s; ++c)
                    box = (box << k[c]) |
                          static_cast<std::size_t>(std::ldexp(p[c], k[c]));  // floor(p·2^k)
                ++count[box];
            }
            for (const int n : count)
                if (n != 1 << t) return false;
            return true;
        }
        for (k[j] = 0; k[j] <= left; ++k[j])
            if (!compositions(j + 1, left - k[j])) return false;
        return true;
    };
    return compositions(0, m - t);
}

TEST(SobolSampler, UnscrambledPointsAreTheSobolSequence) {
    // The first points of Sobol's first three dimensions in index order (dimension 3 from Joe &
    // Kuo's x² + x + 1, m = 1, 3; Bratley & Fox 1988; in Gray-code order these are the first
    // points of SciPy's unscrambled qmc.Sobol(d=3)).
    const double expected[8][3] = {{0, 0, 0},
                                   {0.5, 0.5, 0.5},
                                   {0.25, 0.75, 0.75},
                                   {0.75, 0.25, 0.25},
                                   {0.125, 0.625, 0.375},
                                   {0.625, 0.125, 0.875},
                                   {0.375, 0.375, 0.625},
                                   {0.875, 0.875, 0.125}};
    for (std::uint32_t i = 0; i < 8; ++i)
        for (int d = 0; d < 3; ++d)
            EXPECT_EQ(sobol_coordinate(i, d) * 0x1.0p-32, expected[i][d]) << i << " " << d;
}

/// Degree of the primitive polynomial of each Sobol dimension the prefix may use (x, x + 1, then
/// Joe & Kuo's): the sequence's t is the sum of (degree − 1) over the dimensions taken.
constexpr std::array<int, kSobolDimensions> kPolynomialDegree = {1, 1, 2, 3, 3, 4, 4};

/// The first 2^m unscrambled Sobol points in `dimensions`.
std::vector<std::vector<double>> sobol_points(const std::vector<int>& dimensions, int m) {
    std::vector<std::vector<double>> points;
    for (std::uint32_t i = 0; i < (1u << m); ++i) {
        std::vector<double> p;
        for (const int d : dimensions) p.push_back(sobol_coordinate(i, d) * 0x1.0p-32);
        points.push_back(p);
    }
    return points;
}

TEST(SobolSampler, SobolDimensionsAreNetsWithTheirPolynomialsT) {
    // Checks the direction numbers: a wrong column breaks the net property of some projection.
    for (int m = 0; m <= 10; ++m) {
        for (int d = 0; d < kSobolDimensions; ++d) {
            ASSERT_TRUE(is_net(sobol_points({d}, m), m, 0)) << "dimension " << d << ", m " << m;
            for (int e = d + 1; e < kSobolDimensions; ++e) {
                const int t = std::min(m, kPolynomialDegree[d] + kPolynomialDegree[e] - 2);
                EXPECT_TRUE(is_net(sobol_points({d, e}, m), m, t))
                    << "dimensions " << d << ", " << e << ", m " << m;
            }
        }
        EXPECT_TRUE(is_net(sobol_points({0, 1, 2, 3, 4}, m), m, std::min(m, 0 + 0 + 1 + 2 + 2)))
            << "m " << m;
    }
}

/// The prefix of `points` = 2^m samples of one replicate, as the renderer draws it (PathSampler):
/// sub-pixel x, y, wavelength, then each prefix bounce's pair, per sample.
std::vector<std::vector<double>> path_prefixes(const ReplicateSampler& replicate) {
    std::vector<std::vector<double>> out;
    for (std::uint32_t i = 0; i < replicate.points(); ++i) {
        PathSampler path(replicate, i, 1, 2, i);
        std::vector<double> p;
        for (const double u : path.subpixel()) p.push_back(u);
        p.push_back(path.wavelength());
        for (int b = 0; b < kPrefixBounces; ++b)
            for (const double u : path.scatter(b)) p.push_back(u);
        out.push_back(p);
    }
    return out;
}

/// Coordinates `which` of each of `points`.
std::vector<std::vector<double>> projection(const std::vector<std::vector<double>>& points,
                                            const std::vector<int>& which) {
    std::vector<std::vector<double>> out;
    for (const auto& p : points) {
        std::vector<double> q;
        for (const int c : which) q.push_back(p[static_cast<std::size_t>(c)]);
        out.push_back(q);
    }
    return out;
}

TEST(SobolSampler, ScrambledPathPrefixesAreJointNets) {
    // The path's prefix numbers, drawn sample by sample as the renderer does, keep the nets of
    // their Sobol dimensions after scrambling and the shared permutation: the first bounce's pair a
    // (0,m,2)-net, with the wavelength a (1,m,3)-net, the sub-pixel and second bounce's pairs
    // (t ≤ 2)-nets (Joe & Kuo's two-dimensional projections, sobol_sampler.h), and the five numbers
    // of sub-pixel, wavelength and first bounce jointly a net with t = Σ (degree − 1). A
    // permutation per number would leave each coordinate stratified but break every joint net.
    static_assert(kPrefixBounces == 2);
    const std::vector<int> subpixel = {0, 1}, first_bounce = {3, 4}, second_bounce = {5, 6};
    int t5 = 0;
    for (const int c : {0, 1, 2, 3, 4})
        t5 += kPolynomialDegree[static_cast<std::size_t>(kPrefixSobolDimensions[c])] - 1;
    for (int m = 0; m <= 8; ++m)
        for (std::uint64_t pixel : {0ull, 4711ull})
            for (std::uint32_t replicate : {0u, 5u}) {
                const auto points = path_prefixes(ReplicateSampler(3, pixel, replicate, 1u << m));
                const std::string what = "m " + std::to_string(m) + " pixel " +
                                         std::to_string(pixel) + " replicate " +
                                         std::to_string(replicate);
                for (int c = 0; c < kPrefixSize; ++c)
                    ASSERT_TRUE(is_net(projection(points, {c}), m, 0)) << what << " number " << c;
                EXPECT_TRUE(is_net(projection(points, first_bounce), m, 0)) << what;
                EXPECT_TRUE(is_net(projection(points, {2, 3, 4}), m, std::min(m, 1))) << what;
                EXPECT_TRUE(is_net(projection(points, subpixel), m, std::min(m, 2))) << what;
                EXPECT_TRUE(is_net(projection(points, second_bounce), m, std::min(m, 2))) << what;
                EXPECT_TRUE(is_net(projection(points, {0, 1, 2, 3, 4}), m, std::min(m, t5)))
                    << what;
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
    std::vector<double> subpixel_x, wavelength, bounce_u1, prefix_next_replicate;
    std::vector<int> histogram(16, 0);
    std::vector<std::vector<int>> prefix_histograms(kPrefixSize, std::vector<int>(16, 0));
    for (std::uint32_t r = 0; r < 2000; ++r) {
        const ReplicateSampler a(1, 77, r, kPoints), b(1, 77, r + 5000, kPoints),
            c(1, 78, r, kPoints);
        for (std::uint32_t i = 0; i < kPoints; ++i) {
            slot0.push_back(a.pair(i, 0)[0]);
            slot2.push_back(a.pair(i, 2)[1]);
            slot3.push_back(a.single(i, 3));
            next_replicate.push_back(b.pair(i, 0)[0]);
            next_pixel.push_back(c.pair(i, 0)[0]);
            subpixel_x.push_back(a.prefix(a.prefix_point(i), 0));
            wavelength.push_back(a.prefix(a.prefix_point(i), 2));
            bounce_u1.push_back(a.prefix(a.prefix_point(i), 3));
            prefix_next_replicate.push_back(b.prefix(b.prefix_point(i), 0));
        }
        ++histogram[static_cast<std::size_t>(a.pair(0, 0)[1] * 16.0)];  // one point's distribution
        for (int c = 0; c < kPrefixSize; ++c)
            ++prefix_histograms[static_cast<std::size_t>(c)]
                               [static_cast<std::size_t>(a.prefix(a.prefix_point(0), c) * 16.0)];
    }
    EXPECT_LT(std::abs(correlation(slot0, slot2)), 0.03);
    EXPECT_LT(std::abs(correlation(slot0, slot3)), 0.03);
    EXPECT_LT(std::abs(correlation(slot2, slot3)), 0.03);
    EXPECT_LT(std::abs(correlation(slot0, next_replicate)), 0.03);
    EXPECT_LT(std::abs(correlation(slot0, next_pixel)), 0.03);
    EXPECT_LT(std::abs(correlation(subpixel_x, wavelength)), 0.03);
    EXPECT_LT(std::abs(correlation(subpixel_x, bounce_u1)), 0.03);
    EXPECT_LT(std::abs(correlation(wavelength, bounce_u1)), 0.03);
    EXPECT_LT(std::abs(correlation(subpixel_x, prefix_next_replicate)), 0.03);
    EXPECT_LT(std::abs(correlation(bounce_u1, slot2)), 0.03);
    // The first point of 2000 replicates in 16 bins: χ² with 15 dof; P(χ²₁₅ > 40) = 4e-4.
    const auto chi2 = [](const std::vector<int>& counts) {
        double sum = 0.0;
        for (const int h : counts) sum += std::pow(h - 125.0, 2) / 125.0;
        return sum;
    };
    EXPECT_LT(chi2(histogram), 40.0);
    for (int c = 0; c < kPrefixSize; ++c)
        EXPECT_LT(chi2(prefix_histograms[static_cast<std::size_t>(c)]), 40.0) << "number " << c;
}

TEST(SobolSampler, PathSamplerTakesPrefixSlotsAndStreamInTurn) {
    const ReplicateSampler replicate(1, 2, 3, 8);
    SampleStream reference(1, 2, 3);
    PathSampler path(replicate, 5, 1, 2, 3);  // its stream is SampleStream(1, 2, 3)
    const std::uint32_t point = replicate.prefix_point(5);
    EXPECT_EQ(path.subpixel()[1], replicate.prefix(point, 1));
    EXPECT_EQ(path.wavelength(), replicate.prefix(point, 2));
    EXPECT_EQ(path.scatter(kPrefixBounces - 1)[1], replicate.prefix(point, kPrefixSize - 1));
    EXPECT_EQ(path.scatter(kPrefixBounces), replicate.pair(5, 2 * kPrefixBounces));
    EXPECT_EQ(path.roulette(kSobolBounces - 1), replicate.single(5, 2 * kSobolBounces - 1));
    const auto deep = path.scatter(kSobolBounces);
    EXPECT_EQ(deep[0], reference.next());
    EXPECT_EQ(deep[1], reference.next());
}

}  // namespace
}  // namespace tirpol::simulation
