// Noise: the 3D noise decomposition (D'Agostino & Webb 1991) recovers planted components; NEDT
// from temporal noise and responsivity; NEDT falls as 1/√n for white noise.

#include "tirpol/calibration/noise.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tirpol/core/error.h"

namespace tirpol::calibration {
namespace {

struct Planted {
    double t, v, h, vh, tvh;
};

FrameStack synthetic_stack(int w, int h, int nt, const Planted& p, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> unit(0.0, 1.0);
    std::vector<double> row(static_cast<std::size_t>(h)), col(static_cast<std::size_t>(w)),
        fpn(static_cast<std::size_t>(w * h));
    for (auto& x : row) x = p.v * unit(rng);
    for (auto& x : col) x = p.h * unit(rng);
    for (auto& x : fpn) x = p.vh * unit(rng);
    FrameStack s{w, h, {}};
    for (int t = 0; t < nt; ++t) {
        const double flicker = p.t * unit(rng);
        std::vector<float> f;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                f.push_back(static_cast<float>(8000.0 + flicker + row[static_cast<std::size_t>(y)] +
                                               col[static_cast<std::size_t>(x)] +
                                               fpn[static_cast<std::size_t>(y * w + x)] +
                                               p.tvh * unit(rng)));
        s.frames.push_back(std::move(f));
    }
    return s;
}

TEST(Noise, ThreeDDecompositionRecoversPlantedComponents) {
    const Planted p{1.5, 4.0, 3.0, 6.0, 5.0};
    const auto stack = synthetic_stack(96, 80, 64, p, 1);
    const ThreeDNoise n = three_d_noise(stack);
    // Sampling error: σ_v from 80 rows and σ_h from 96 columns ≈ 8 %, σ_t from 64 frames ≈ 9 %.
    EXPECT_NEAR(n.sigma_tvh, p.tvh, 0.03 * p.tvh);
    EXPECT_NEAR(n.sigma_vh, p.vh, 0.05 * p.vh);
    EXPECT_NEAR(n.sigma_v, p.v, 0.3 * p.v);
    EXPECT_NEAR(n.sigma_h, p.h, 0.3 * p.h);
    EXPECT_NEAR(n.sigma_t, p.t, 0.35 * p.t);
    // No temporal row/column noise was planted: these components only hold the random noise that
    // survives the directional average, σ_tvh·√((1 − 1/nt)(1 − 1/nv)/nh) — the known bias of the
    // estimator (D'Agostino & Webb 1991), 0.504 for N_tv and 0.553 for N_th here.
    EXPECT_NEAR(n.sigma_tv, p.tvh * std::sqrt((1.0 - 1.0 / 64) * (1.0 - 1.0 / 80) / 96.0), 0.05);
    EXPECT_NEAR(n.sigma_th, p.tvh * std::sqrt((1.0 - 1.0 / 64) * (1.0 - 1.0 / 96) / 80.0), 0.05);
    EXPECT_NEAR(n.mean, 8000.0, 2.0);
}

TEST(Noise, DecompositionIsExactlyAdditive) {
    // The components are orthogonal, so their variances add up to the total variance of the cube.
    const auto stack = synthetic_stack(20, 16, 10, {1.0, 2.0, 3.0, 4.0, 5.0}, 2);
    const ThreeDNoise n = three_d_noise(stack);
    double ss = 0.0;
    for (const auto& f : stack.frames)
        for (float u : f) ss += (u - n.mean) * (u - n.mean);
    EXPECT_NEAR(n.sigma_total * n.sigma_total, ss / (20.0 * 16.0 * 10.0), 1e-6 * ss);
}

TEST(Noise, NedtIsTemporalNoiseOverResponsivityAndFallsAsInverseRootOfFramesAveraged) {
    // Responsivity 70 counts/K (gain 100 counts per W/(m²·sr) × dL/dT 0.7 W/(m²·sr·K)); temporal σ
    // 5.6 counts → NEDT 80 mK, the paper's camera without the polarizer (§3.1).
    const auto stack = synthetic_stack(64, 48, 64, {0.0, 0.0, 0.0, 3.0, 5.6}, 3);
    const std::vector<float> responsivity(64 * 48, 70.0f);
    const auto nedt = nedt_map(temporal_noise(stack), responsivity);
    EXPECT_NEAR(finite_median(nedt), 0.080, 0.003);
    const auto curve = nedt_vs_averaging(stack, responsivity);
    ASSERT_EQ(curve.size(), 5u);  // n = 1, 2, 4, 8, 16 (≥ 4 means each)
    EXPECT_EQ(curve.back().frames_averaged, 16);
    for (const auto& pt : curve)
        EXPECT_NEAR(pt.median_nedt_k / pt.white_noise_k, 1.0, 0.2) << pt.frames_averaged;
}

TEST(Noise, TooFewFramesOrBadFramesAreRejected) {
    FrameStack one{2, 2, {{1, 2, 3, 4}}};
    EXPECT_THROW(validate_stack(one, "stack.exr"), Error);
    FrameStack bad{2, 2, {{1, 2, 3, 4}, {1, 2, 3}}};
    EXPECT_THROW(validate_stack(bad, "stack.exr"), Error);
}

}  // namespace
}  // namespace tirpol::calibration
