// couple_simulated_polarizer: a simulated camera opened by URI, then coupled to the stage opened by
// URI, shows the scene through the polarizer where that stage has it — the in-process sim:// stage
// (time-true, also mid-move) and a driver stage speaking the APT protocol to tirpol's stage
// simulator on a pseudo-terminal (the angle its driver reached). Without the coupling every frame
// was exposed at 0°, and a 0/45/90/135 set of an unpolarized-looking scene gave S1 = S2 = 0.

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "stage_simulator_thread.h"
#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/frame_gate.h"
#include "tirpol/acquisition/internal/sim_stage.h"
#include "tirpol/acquisition/sim/simulated_camera.h"
#include "tirpol/acquisition/stage.h"

namespace tirpol::acquisition {
namespace {

using namespace std::chrono_literals;

/// A camera whose counts are 10 × the polarizer angle it sees, free-running at 200 Hz.
std::unique_ptr<SimulatedCamera> angle_reporting_camera() {
    SimulatedCameraConfig config;
    config.width = 4;
    config.height = 2;
    config.frame_rate_hz = 200.0;
    return std::make_unique<SimulatedCamera>(config, [](double angle_deg, std::vector<float>& out) {
        std::fill(out.begin(), out.end(), static_cast<float>(10.0 * angle_deg));
    });
}

/// The angle the first frame exposed after now shows.
double angle_seen_now(Camera& camera) {
    const std::int64_t after_ns = host_realtime_ns();
    Frame frame = camera.grab(2s).value();
    while (frame.host_timestamp_ns <= after_ns) frame = camera.grab(2s).value();
    return frame.counts[0] / 10.0;
}

TEST(SimulatedPolarizer, CameraSeesTheAngleOfAnInProcessStage) {
    auto camera = angle_reporting_camera();
    auto stage = couple_simulated_polarizer(*camera, open_stage("sim://").value_or_throw());
    ASSERT_TRUE(stage->home(2s).ok());
    ASSERT_TRUE(camera->start().ok());
    for (double a : {0.0, 45.0, 90.0, 135.0}) {
        ASSERT_TRUE(stage->move_absolute(a, 2s).ok());
        EXPECT_NEAR(angle_seen_now(*camera), a, 0.05) << "stage at " << a << "°";
    }
}

TEST(SimulatedPolarizer, CameraSeesTheAngleADriverStageReached) {
    StageSimulatorOptions options;
    options.protocol = SimProtocol::Apt;
    options.deg_per_s = 360.0;
    test::StageSimulatorThread simulator(options);
    auto camera = angle_reporting_camera();
    auto stage = couple_simulated_polarizer(
        *camera, open_stage("thorlabs-apt://" + simulator.path()).value_or_throw());
    ASSERT_TRUE(camera->start().ok());
    ASSERT_TRUE(stage->home(10s).ok());
    EXPECT_NEAR(angle_seen_now(*camera), 0.0, 0.05);
    for (double a : {45.0, 90.0, 135.0}) {
        ASSERT_TRUE(stage->move_absolute(a, 10s).ok());
        EXPECT_NEAR(angle_seen_now(*camera), a, 0.05) << "stage at " << a << "°";
    }
}

TEST(SimulatedPolarizer, TheCameraOutlivesItsStage) {
    auto camera = angle_reporting_camera();
    {
        auto stage = couple_simulated_polarizer(*camera, open_stage("sim://").value_or_throw());
        ASSERT_TRUE(stage->home(2s).ok());
        ASSERT_TRUE(stage->move_absolute(60.0, 2s).ok());
    }
    ASSERT_TRUE(camera->start().ok());
    EXPECT_NEAR(angle_seen_now(*camera), 60.0, 0.05);  // the last angle reached, no dangling stage
}

TEST(SimulatedPolarizer, ACameraWithItsOwnAngleSourceIsLeftAlone) {
    auto stage = make_simulated_stage("sim://");
    SimulatedCameraConfig config;
    config.width = 2;
    config.height = 1;
    SimulatedCamera camera(
        config,
        [](double a, std::vector<float>& out) {
            std::fill(out.begin(), out.end(), static_cast<float>(a));
        },
        [] { return 30.0; });
    Stage* raw = stage.get();
    auto same = couple_simulated_polarizer(camera, std::move(stage));
    EXPECT_EQ(same.get(), raw);
}

}  // namespace
}  // namespace tirpol::acquisition
