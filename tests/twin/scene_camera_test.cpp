// The renderer-backed camera sim://<scene.yaml>, opened through acquisition's ordinary camera
// registry once the twin registered it: a frame's counts are the rendered Stokes image through the
// twin's wire grid and detector, C = g·(½(τ + τ/ER)·S0 + ½(τ − τ/ER)·S1 + ρ·L_r + ε·L_bb(T_grid)) +
// o at 0° (linear diattenuator, Chipman, Lam & Young 2018 eq 6.35), within the detector's temporal
// noise σ = g·NEDT·dL/dT(T_ref).

#include "tirpol/twin/scene_camera.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <vector>

#include "tirpol/acquisition/camera.h"
#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/stage.h"
#include "tirpol/core/error.h"
#include "tirpol/core/source_tree.h"
#include "tirpol/simulation/renderer.h"
#include "tirpol/simulation/scene.h"
#include "tirpol/twin/instrument.h"

namespace tirpol::twin {
namespace {

using namespace std::chrono_literals;

constexpr int kWidth = 24, kHeight = 18, kSpp = 2;

/// The scene camera's own render of panels_night at kWidth × kHeight, kSpp (the renderer is
/// deterministic for a scene and its settings), and the twin instrument's constants that turn it
/// into counts.
struct ExpectedCounts {
    Image stokes;
    double tau, tau_min;  ///< the wire grid's transmissions along and across its axis
    double g, o;          ///< detector gain (counts per W/(m²·sr)) and offset
    double grid;          ///< what the grid reflects and emits, W/(m²·sr)
    double sigma;         ///< temporal noise of one frame, counts
};

ExpectedCounts expected_counts() {
    simulation::Scene scene = simulation::load_scene(find_config("scenes/panels_night.yaml"));
    scene.camera = scene.camera.resized(kWidth, kHeight);
    scene.sampling.samples_per_pixel = kSpp;
    const simulation::SensorModel sensor = twin_sensor(scene.band, scene.sky.temperature_k(1.0));
    ExpectedCounts e;
    e.stokes = simulation::render(scene);
    e.tau = sensor.analyzer.transmission;
    e.tau_min = e.tau / sensor.analyzer.extinction_ratio;
    e.g = sensor.counts->gain_counts_per_radiance;
    e.o = sensor.counts->offset_counts;
    e.grid = sensor.background.reflectance * sensor.background.reflected_radiance +
             sensor.background.emissivity * scene.band.radiance(sensor.background.temperature_k);
    e.sigma = e.g * sensor.counts->nedt_k *
              scene.band.radiance_dT(sensor.counts->reference_temperature_k);
    return e;
}

TEST(SceneCamera, FrameCountsFollowTheRenderedRadiance) {
    register_twin_device_schemes();
    auto opened = acquisition::open_camera(
        "sim://config/scenes/panels_night.yaml?width=24&height=18&spp=2&fps=50");
    ASSERT_TRUE(opened.ok()) << opened.error().message;
    auto& camera = *opened.value();
    EXPECT_EQ(camera.info().width, kWidth);
    ASSERT_TRUE(camera.start().ok());
    const acquisition::Frame frame = camera.grab(10s).value();
    ASSERT_EQ(frame.counts.size(), static_cast<std::size_t>(kWidth * kHeight));

    const ExpectedCounts e = expected_counts();
    const Image& stokes = e.stokes;
    const double tau = e.tau, tau_min = e.tau_min, g = e.g, o = e.o, grid = e.grid, sigma = e.sigma;
    ASSERT_GT(sigma, 0.0);

    const auto& s0 = stokes.channel("S0");
    const auto& s1 = stokes.channel("S1");
    double sum_z = 0.0, s0_min = 1e300, s0_max = -1e300;
    for (std::size_t i = 0; i < frame.counts.size(); ++i) {
        const double expected =
            g * (0.5 * (tau + tau_min) * s0[i] + 0.5 * (tau - tau_min) * s1[i] + grid) + o;
        const double z = (frame.counts[i] - expected) / sigma;
        EXPECT_LT(std::abs(z), 6.0)
            << "pixel " << i << ": counts " << frame.counts[i] << ", expected " << expected;
        sum_z += z;
        s0_min = std::min(s0_min, static_cast<double>(s0[i]));
        s0_max = std::max(s0_max, static_cast<double>(s0[i]));
    }
    // Unbiased: the mean z of N pixels has σ = 1/√N (+ rounding to whole counts, ≤ 0.5/σ).
    EXPECT_LT(std::abs(sum_z / static_cast<double>(frame.counts.size())),
              5.0 / std::sqrt(frame.counts.size()) + 0.5 / sigma);
    // The scene has contrast well above the noise (sky vs panels), so the check above is not
    // vacuous.
    EXPECT_GT(g * 0.5 * tau * (s0_max - s0_min), 50.0 * sigma);
}

TEST(SceneCamera, FramesFollowACoupledStageSoTheScenesPolarizationAppears) {
    // Behind a stage, I(0°) − I(90°) = g·(τ − τ/ER)·S1 per pixel (the counts formula above): the
    // rendered S1 appears in the frames. Before the coupling every frame was exposed at 0° and the
    // difference was noise only.
    register_twin_device_schemes();
    auto camera = acquisition::open_camera(
                      "sim://config/scenes/panels_night.yaml?width=24&height=18&spp=2&fps=100")
                      .value_or_throw();
    auto stage = acquisition::couple_simulated_polarizer(
        *camera, acquisition::open_stage("sim://").value_or_throw());
    ASSERT_TRUE(stage->home(2s).ok());
    ASSERT_TRUE(camera->start().ok());
    constexpr int kFrames = 8;
    auto mean_frame_at = [&](double angle_deg) {
        EXPECT_TRUE(stage->move_absolute(angle_deg, 2s).ok());
        const std::int64_t moved_ns =  // host timestamps are CLOCK_REALTIME
            std::chrono::duration_cast<std::chrono::nanoseconds>(
                std::chrono::system_clock::now().time_since_epoch())
                .count();
        std::vector<double> sum(static_cast<std::size_t>(kWidth * kHeight), 0.0);
        for (int k = 0; k < kFrames;) {
            const acquisition::Frame f = camera->grab(10s).value();
            if (f.host_timestamp_ns <= moved_ns) continue;  // exposed before the move ended
            for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += f.counts[i] / kFrames;
            ++k;
        }
        return sum;
    };
    const std::vector<double> i0 = mean_frame_at(0.0), i90 = mean_frame_at(90.0);

    const ExpectedCounts e = expected_counts();
    const auto& s1 = e.stokes.channel("S1");
    double measured = 0.0, expected = 0.0;
    for (std::size_t i = 0; i < i0.size(); ++i) {
        measured += i0[i] - i90[i];
        expected += e.g * (e.tau - e.tau_min) * s1[i];
    }
    const auto n = static_cast<double>(i0.size());
    const double sigma_sum =
        e.sigma * std::sqrt(2.0 * n / kFrames);  // two means of kFrames frames, n pixels
    EXPECT_NEAR(measured, expected, 5.0 * sigma_sum + 0.5 * n);  // + rounding to whole counts
    EXPECT_GT(std::abs(expected), 20.0 * sigma_sum)
        << "the scene's S1 must be resolvable for this test to mean anything";
}

TEST(SceneCamera, OtherSimTargetsStillReachTheBuiltInCamera) {
    register_twin_device_schemes();
    auto camera = acquisition::open_camera("sim://uniform?width=2&height=2&counts=77");
    ASSERT_TRUE(camera.ok());
    ASSERT_TRUE(camera.value()->start().ok());
    const acquisition::Frame frame = camera.value()->grab(2s).value();
    ASSERT_EQ(frame.counts.size(), 4u);
    for (float v : frame.counts) EXPECT_EQ(v, 77.0f);
}

TEST(SceneCamera, MissingSceneFileAndUnknownKeysAreNamed) {
    register_twin_device_schemes();
    auto error_of = [](const std::string& uri) -> std::string {
        try {
            (void)acquisition::open_camera(uri);
        } catch (const Error& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_NE(error_of("sim://no/such/scene.yaml").find("no/such/scene.yaml"), std::string::npos);
    EXPECT_NE(error_of("sim://config/scenes/panels_night.yaml?zoom=2").find("zoom"),
              std::string::npos);
}

}  // namespace
}  // namespace tirpol::twin
