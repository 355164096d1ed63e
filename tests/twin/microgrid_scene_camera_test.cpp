// The renderer-backed camera sim://<scene.yaml> as a microgrid (DoFP) camera outside the twin:
// `microgrid=sony` puts simulation/dofp_sensor.h's sensor (each pixel its own micro-polarizer and
// bolometer) behind the rendered scene. A frame's counts are DofpSensor::expected_counts of the
// camera's own render within the sensor's temporal noise, and `tirpol acquire`'s capture loop
// records it into a session that keeps the pattern, so that the session reduces to the scene's
// Stokes image as the sensor sees it.

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "test_support.h"
#include "tirpol/acquisition/camera.h"
#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/stage.h"
#include "tirpol/calibration/microgrid_session.h"
#include "tirpol/calibration/microgrid_stokes.h"
#include "tirpol/core/error.h"
#include "tirpol/core/session.h"
#include "tirpol/core/source_tree.h"
#include "tirpol/simulation/dofp_sensor.h"
#include "tirpol/simulation/renderer.h"
#include "tirpol/simulation/scene.h"
#include "tirpol/twin/scene_camera.h"

namespace tirpol::twin {
namespace {

using namespace std::chrono_literals;

constexpr int kWidth = 24, kHeight = 18;
constexpr const char* kUri =
    "sim://config/scenes/panels_night.yaml?width=24&height=18&spp=2&fps=50&microgrid=sony";

/// The noise-free counts of the camera: its own render (deterministic for the scene and its
/// settings) through the sensor of DofpSensorSpec's defaults, Sony pattern, seed 1.
struct Expected {
    std::vector<float> counts;
    double sigma = 0.0;
};

Expected expected() {
    simulation::Scene scene = simulation::load_scene(find_config("scenes/panels_night.yaml"));
    scene.camera = scene.camera.resized(kWidth, kHeight);
    scene.sampling.samples_per_pixel = 2;
    const simulation::DofpSensor sensor(simulation::DofpSensorSpec{}, kWidth, kHeight, scene.band);
    return {sensor.expected_counts(simulation::render(scene)), sensor.noise_sigma_counts()};
}

TEST(MicrogridSceneCamera, FramesAreTheRenderThroughTheDofpSensor) {
    register_twin_device_schemes();
    auto camera = acquisition::open_camera(kUri).value_or_throw();
    ASSERT_TRUE(camera->info().microgrid_pattern_deg);
    EXPECT_EQ(*camera->info().microgrid_pattern_deg, (std::array<double, 4>{90, 45, 135, 0}));
    ASSERT_TRUE(camera->start().ok());
    const acquisition::Frame frame = camera->grab(10s).value();
    const Expected e = expected();
    ASSERT_EQ(frame.counts.size(), e.counts.size());
    ASSERT_GT(e.sigma, 0.0);
    double sum_z = 0.0, min_counts = 1e300, max_counts = -1e300;
    for (std::size_t i = 0; i < e.counts.size(); ++i) {
        const double z = (frame.counts[i] - e.counts[i]) / e.sigma;
        EXPECT_LT(std::abs(z), 6.0) << "pixel " << i;
        sum_z += z;
        min_counts = std::min(min_counts, static_cast<double>(e.counts[i]));
        max_counts = std::max(max_counts, static_cast<double>(e.counts[i]));
    }
    // Unbiased (the mean z of N pixels has σ 1/√N, plus the ADC's rounding ≤ 0.5/σ), and the
    // scene's contrast is far above the noise, so the check is not vacuous.
    EXPECT_LT(std::abs(sum_z / static_cast<double>(e.counts.size())),
              5.0 / std::sqrt(static_cast<double>(e.counts.size())) + 0.5 / e.sigma);
    EXPECT_GT(max_counts - min_counts, 50.0 * e.sigma);
}

TEST(MicrogridSceneCamera, AcquiredSessionRecordsThePatternAndReducesToTheSensorsStokes) {
    register_twin_device_schemes();
    auto camera = acquisition::open_camera(kUri).value_or_throw();
    auto stage = acquisition::couple_simulated_polarizer(
        *camera, acquisition::open_stage("sim://").value_or_throw());
    acquisition::CapturePlan plan;
    plan.angles_deg = {0.0};  // a microgrid camera needs no polarizer turn
    plan.frames_per_angle = 8;
    plan.settle_s = 0.0;
    test::TempDir tmp;
    {
        auto session = SessionWriter::create(
            tmp / "s", acquisition::new_session_manifest(camera->info(), stage->info(), plan));
        acquisition::CaptureOptions options;
        options.progress_stream = nullptr;
        acquisition::run_capture(*camera, *stage, plan, session, options);
    }
    ASSERT_TRUE(calibration::is_microgrid_session(tmp / "s"));
    calibration::MicrogridSessionOptions options;
    options.method = calibration::DemosaicMethod::SuperPixel;
    const Image measured = calibration::reduce_microgrid_session(tmp / "s", options);
    // The same reduction of the noise-free counts: the session's mean of 8 frames differs by
    // noise only (per super-pixel S0 = ½ΣI has σ/√8, S1 = I0 − I90 and S2 √2·σ/√8).
    const Expected e = expected();
    calibration::MicrogridReductionOptions reference_options;
    reference_options.method = calibration::DemosaicMethod::SuperPixel;
    const Image reference = calibration::reduce_microgrid(
        e.counts, kWidth, kHeight, calibration::MicrogridPattern::sony_imx250mzr(),
        reference_options);
    ASSERT_EQ(measured.pixel_count(), reference.pixel_count());
    const double sigma = std::sqrt(2.0) * e.sigma / std::sqrt(8.0);
    for (const char* name : {"S0", "S1", "S2"})
        for (std::size_t i = 0; i < measured.pixel_count(); ++i)
            ASSERT_NEAR(measured.channel(name)[i], reference.channel(name)[i], 6.0 * sigma)
                << name << " super-pixel " << i;
    EXPECT_EQ(std::get<int>(measured.attributes().at("frames_averaged")), 8);
}

TEST(MicrogridSceneCamera, RefusesOddSizesABadPatternAndASeedWithoutAMicrogrid) {
    const std::pair<const char*, const char*> cases[] = {
        {"sim://config/scenes/panels_night.yaml?width=23&height=18&spp=1&microgrid=sony", "even"},
        {"sim://config/scenes/panels_night.yaml?width=24&height=18&spp=1&microgrid=0,0,90,45",
         "microgrid"},
        {"sim://config/scenes/panels_night.yaml?width=24&height=18&spp=1&seed=3", "seed"}};
    for (const auto& [uri, needle] : cases) {
        try {
            open_scene_camera(uri);
            ADD_FAILURE() << "accepted " << uri;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
        }
    }
}

}  // namespace
}  // namespace tirpol::twin
