// Requires TIRPOL_WITH_ARAVIS (built only with that back end: cmake/TirpolBackends.cmake).
// The microgrid path end to end on a simulated camera: a free-running GigE Vision microgrid camera
// (FakeGigECameraServer over real GVCP/GVSP on loopback,
// tests/data/genicam/polarized-fake-camera.xml, LUCID's PolarizeMono12p raw mosaic, its own 30 Hz
// clock) images a known smooth Stokes scene through ideal analyzers in the Sony IMX250MZR layout,
// plus noise. `run_capture` records it into a session (one step; a microgrid camera needs no
// polarizer turn, so the stage stays at 0°), the session records the camera's pattern, and the
// recorded frame — demosaiced (newton) and reduced with the pattern read back from the session —
// gives the scene's Stokes image within noise.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "../acquisition/fake_gv_camera_process.h"
#include "test_support.h"
#include "tirpol/acquisition/camera.h"
#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/internal/sim_stage.h"
#include "tirpol/acquisition/sim/fake_gige_server.h"
#include "tirpol/calibration/microgrid_stokes.h"
#include "tirpol/core/session.h"

namespace tirpol::acquisition {
namespace {

constexpr int kWidth = 64, kHeight = 48;
constexpr double kNoiseCounts = 6.0;
constexpr double kPolarizedCounts = 600.0;
constexpr int kFrames = 8;

struct Stokes {
    double s0, s1, s2;
};

/// A smooth scene: S0 ramps across the image, DoLP ≈ 0.27, AoP turning 0.5° per column from 20°.
Stokes truth(int x, int y) {
    const double s0 = 2000.0 + 5.0 * x + 2.0 * y;
    const double twice_aop = 2.0 * (20.0 + 0.5 * x) * std::numbers::pi / 180.0;
    return {s0, kPolarizedCounts * std::cos(twice_aop), kPolarizedCounts * std::sin(twice_aop)};
}

TEST(MicrogridCapture, FakePolarizedCameraToSessionToStokesWithinNoise) {
    test::LoopbackGigELock gige_lock;
    FakeGigECameraOptions camera_options;
    camera_options.genicam_xml =
        test::source_dir() / "tests/data/genicam/polarized-fake-camera.xml";
    FakeGigECameraServer server(camera_options);
    const auto sony = calibration::MicrogridPattern::sony_imx250mzr();
    std::mt19937_64 rng(28);
    server.set_fill([&](const FakeGigEFrameRequest& request, std::vector<float>& counts) {
        std::normal_distribution<double> noise(0.0, kNoiseCounts);
        for (int y = 0; y < request.height; ++y)
            for (int x = 0; x < request.width; ++x) {
                const Stokes s = truth(x, y);
                const double t = 2.0 * sony.angle_at_pixel_deg(x, y) * std::numbers::pi / 180.0;
                counts[static_cast<std::size_t>(y * request.width + x)] = static_cast<float>(
                    0.5 * (s.s0 + s.s1 * std::cos(t) + s.s2 * std::sin(t)) + noise(rng));
            }
    });

    auto camera =
        open_camera(
            fmt::format("aravis://{}?pixel_format=PolarizeMono12p&width={}&height={}&fps=30",
                        server.device_id(), kWidth, kHeight))
            .value_or_throw();
    auto stage = make_simulated_stage("sim://", {});
    CapturePlan plan;
    plan.angles_deg = {0.0};
    plan.frames_per_angle = kFrames;
    plan.settle_s = 0.0;
    test::TempDir tmp;
    {
        auto session = SessionWriter::create(
            tmp / "s", new_session_manifest(camera->info(), stage->info(), plan));
        CaptureOptions options;
        options.progress_stream = nullptr;
        run_capture(*camera, *stage, plan, session, options);
    }

    const SessionManifest m = read_session(tmp / "s");
    ASSERT_TRUE(m.complete);
    ASSERT_EQ(m.records.size(), 1u);
    EXPECT_EQ(m.camera.pixel_format, "PolarizeMono12p");
    EXPECT_EQ(m.camera.bits_per_pixel, 12);
    ASSERT_TRUE(m.camera.microgrid_pattern_deg) << "the session records the camera's pattern";
    const calibration::MicrogridPattern pattern(*m.camera.microgrid_pattern_deg, "session");
    EXPECT_EQ(pattern.angles_deg(), sony.angles_deg());

    const Image frame = read_session_frame(tmp / "s", m, m.records[0]);
    calibration::MicrogridReductionOptions options;
    options.method = calibration::DemosaicMethod::Newton;
    const Image stokes =
        calibration::reduce_microgrid(frame.channel("counts"), kWidth, kHeight, pattern, options);
    // Noise of the mean of 8 frames: σ/√8 ≈ 2.1 counts per pixel, and S1 = I0 − I90 from
    // interpolated planes has about √2 times that (≈ 3 counts; docs/microgrid.md: newton's S1 noise
    // is ≈ 0.95 σ_pixel·√2/1.41). The 12-bit rounding adds 0.29 counts. An error in the pattern,
    // the packing or the Stokes convention gives errors of hundreds of counts.
    double sum_sq[3] = {0.0, 0.0, 0.0};
    int n = 0;
    const char* names[3] = {"S0", "S1", "S2"};
    for (int y = 3; y < kHeight - 3; ++y)
        for (int x = 3; x < kWidth - 3; ++x) {
            const Stokes s = truth(x, y);
            const double want[3] = {s.s0, s.s1, s.s2};
            for (int c = 0; c < 3; ++c) {
                const double got =
                    stokes.channel(names[c])[static_cast<std::size_t>(y * kWidth + x)];
                sum_sq[c] += (got - want[c]) * (got - want[c]);
            }
            ++n;
        }
    for (int c = 0; c < 3; ++c) {
        const double rms = std::sqrt(sum_sq[c] / n);
        std::printf("%s RMS error %.2f counts\n", names[c], rms);
        EXPECT_LT(rms, 6.0) << names[c];
        EXPECT_GT(rms, 0.3) << names[c] << ": noise was added, an exact result means no noise "
                            << "reached the frame";
    }
}

}  // namespace
}  // namespace tirpol::acquisition
