// The variance channels are unbiased, not conservative: for two renders a, b with different seeds,
// E(a − b)² = Var a + Var b, so r = Σ(a − b)²/Σ(var_a + var_b) over a material region must be 1.
// The scene is config/scenes/vehicles_night.yaml at 160×128, which the sampler's development did
// not use.
//
// r is itself a random number: over N pixels its standard error is se = √Σ(dᵢ² − r·vᵢ)² / Σvᵢ
// (delta method), ≈ √(2/N) for Gaussian pixel errors but larger where a few pixels carry most of
// Σd² (specular paint, snow). So the test asks that r be consistent with 1 (|r − 1| < 4·se) in
// every region with enough pixels to have power (se ≤ 0.06: the former pair-of-strata estimator,
// conservative by 2–5× in variance, had r = 0.2–0.5 and fails by > 8 se), and that over all regions
// the standardised deviations have mean square near 1 (a systematic bias of 10 % would add
// (0.1/se)² ≈ 4 to it).

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "scene_fixtures.h"

namespace tirpol::simulation {
namespace {

struct RegionRatio {
    double ratio = 0.0, standard_error = 0.0;
};

/// r over the pixels of `material_id` of every pair (a, b) of renders with different seeds.
RegionRatio two_seed_ratio(const std::vector<std::pair<Image, Image>>& pairs,
                           const std::string& channel, float material_id) {
    std::vector<double> d2, v;
    for (const auto& [a, b] : pairs) {
        const auto& id = a.channel("material_id");
        const auto &va = a.channel(channel), &vb = b.channel(channel);
        const auto &var_a = a.channel(channel + "_var"), &var_b = b.channel(channel + "_var");
        for (std::size_t i = 0; i < a.pixel_count(); ++i)
            if (id[i] == material_id) {
                const double d = static_cast<double>(va[i]) - vb[i];
                d2.push_back(d * d);
                v.push_back(static_cast<double>(var_a[i]) + var_b[i]);
            }
    }
    double sum_d2 = 0.0, sum_v = 0.0;
    for (std::size_t i = 0; i < d2.size(); ++i) sum_d2 += d2[i], sum_v += v[i];
    const double r = sum_d2 / sum_v;
    double spread = 0.0;
    for (std::size_t i = 0; i < d2.size(); ++i) spread += std::pow(d2[i] - r * v[i], 2);
    return {r, std::sqrt(spread) / sum_v};
}

TEST(VarianceCalibration, TwoSeedRatioIsOnePerMaterialRegionOnVehiclesNight) {
    Scene scene =
        load_scene(tirpol::test::source_dir() / "config" / "scenes" / "vehicles_night.yaml");
    scene.camera = scene.camera.resized(160, 128);
    int regions_checked = 0;
    double sum_squared_deviation = 0.0;
    for (const int spp : {8, 32})
        for (const bool control_variate : {false, true}) {
            RenderOptions options;
            options.control_variate = control_variate;
            scene.sampling.samples_per_pixel = spp;
            // Two seed pairs: at the default two replicates each pixel's variance has one degree
            // of freedom, and its scatter adds to r's standard error; twice the pixels bring se
            // back to the power the test needs.
            std::vector<std::pair<Image, Image>> pairs;
            for (const std::uint64_t seed : {11, 13}) {
                scene.sampling.seed = seed;
                Image a = render(scene, options);
                scene.sampling.seed = seed + 1;
                pairs.emplace_back(std::move(a), render(scene, options));
            }
            const Image& a = pairs.front().first;
            EXPECT_EQ(std::get<int>(a.attributes().at("variance_dof")),
                      replicate_count(scene.sampling) - 1);
            std::map<float, std::size_t> pixels;
            for (const float id : a.channel("material_id")) ++pixels[id];
            for (const auto& [id, count] : pixels) {
                if (id < 0.0f || count < 1000) continue;
                for (const char* c : {"S0", "S1", "S2"}) {
                    const RegionRatio r = two_seed_ratio(pairs, c, id);
                    const std::string what =
                        fmt::format("{} {} spp {} {} ({} px)", c, spp,
                                    control_variate ? "control-variate" : "plain",
                                    scene.materials[static_cast<std::size_t>(id)].name, count);
                    std::printf("%s: two-seed ratio %.3f ± %.3f\n", what.c_str(), r.ratio,
                                r.standard_error);
                    if (r.standard_error > 0.06) continue;  // too few informative pixels to test
                    ++regions_checked;
                    EXPECT_LT(std::abs(r.ratio - 1.0), 4.0 * r.standard_error) << what;
                    sum_squared_deviation += std::pow((r.ratio - 1.0) / r.standard_error, 2);
                }
            }
        }
    ASSERT_GE(regions_checked, 24);  // ≥ 2 regions × 3 Stokes × 2 spp × 2 estimators
    // χ²/n of n standardised deviations: mean 1, sd √(2/n) ≈ 0.29 at n = 24.
    EXPECT_LT(sum_squared_deviation / regions_checked, 2.0);
}

/// Fewer replicates keep more of the sequence's stratification: one net of 64 points beats 16 nets
/// of 4 (docs/simulation.md "Why R = 2": 1.5–3× lower noise on these scenes), at the price of
/// error bars — one replicate has none (NaN variance, 0 degrees of freedom).
TEST(VarianceCalibration, FewerReplicatesLowerTheNoiseAndOneHasNoVariance) {
    Scene scene =
        load_scene(tirpol::test::source_dir() / "config" / "scenes" / "panels_night.yaml");
    scene.camera = scene.camera.resized(96, 80);
    scene.sampling.samples_per_pixel = 64;
    const auto two_seed_rms = [&](int replicates) {
        scene.sampling.replicates = replicates;
        scene.sampling.seed = 1;
        const Image a = render(scene);
        scene.sampling.seed = 2;
        const Image b = render(scene);
        EXPECT_EQ(std::get<int>(a.attributes().at("variance_dof")), replicates - 1);
        if (replicates == 1) EXPECT_TRUE(std::isnan(a.channel("S1_var")[a.index(48, 40)]));
        double sum = 0.0;
        for (std::size_t i = 0; i < a.pixel_count(); ++i)
            sum += std::pow(a.channel("S1")[i] - b.channel("S1")[i], 2);
        return std::sqrt(sum / static_cast<double>(a.pixel_count()));
    };
    const double one = two_seed_rms(1), sixteen = two_seed_rms(16);
    std::printf("S1 two-seed rms at 64 spp: 1 replicate %.5f, 16 replicates %.5f\n", one, sixteen);
    EXPECT_LT(one, sixteen);
}

}  // namespace
}  // namespace tirpol::simulation
