// Capture plans with drift references: an in-scene reference blackbody region
// and shutter records interleaved with the scene records. The session's plan JSON carries them in
// the form calibration's offset_drift.h reads; the capture loop asks to close and reopen the
// shutter. (Bad drift references: capture_plan_limits_test.cpp.)

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <set>

#include "test_support.h"
#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/internal/sim_stage.h"
#include "tirpol/acquisition/sim/simulated_camera.h"
#include "tirpol/core/error.h"

namespace tirpol::acquisition {
namespace {

using ::testing::HasSubstr;

const char* kPlan = R"(
frames_per_angle: 4
settle_s: 0
repeats: 2
scene_reference:
  roi: {x: 1, y: 1, width: 2, height: 2}
  temperature_c: 30
  temperature_sigma_k: 0.02
shutter_interleave: {every: 4, temperature_k: 295, frames: 3}
)";

TEST(DriftReferencePlan, ShuttersAreInterleavedAtTheNeighbouringAngleAndTheRegionIsStored) {
    const CapturePlan plan = CapturePlan::parse(ConfigNode::parse(kPlan, "plan.yaml"));
    const auto steps = plan_steps(plan);
    ASSERT_EQ(steps.size(), 2u * 4 + 3);  // shutter, 4 scene, shutter, 4 scene, shutter
    std::set<std::string> files;
    for (std::size_t k = 0; k < steps.size(); ++k) {
        files.insert(steps[k].file);
        const bool shutter = k % 5 == 0;
        EXPECT_EQ(steps[k].kind, shutter ? RecordKind::Shutter : RecordKind::Polarizer) << k;
        EXPECT_EQ(steps[k].after_shutter, k % 5 == 1) << k;
        if (shutter) {
            EXPECT_DOUBLE_EQ(*steps[k].temperature_k, 295.0);
            EXPECT_EQ(steps[k].frames, 3);
            EXPECT_DOUBLE_EQ(steps[k].angle_deg, k + 1 < steps.size() ? steps[k + 1].angle_deg
                                                                      : steps[k - 1].angle_deg);
        }
    }
    EXPECT_EQ(files.size(), steps.size());
    const auto json = plan.to_json();
    EXPECT_EQ(json["scene_reference"]["roi"]["width"], 2);
    EXPECT_DOUBLE_EQ(json["scene_reference"]["temperature_k"].get<double>(), 303.15);
    EXPECT_DOUBLE_EQ(json["scene_reference"]["temperature_sigma_k"].get<double>(), 0.02);
    EXPECT_EQ(json["shutter_interleave"]["every"], 4);
    // A plan without them keeps the JSON of earlier versions (what --resume compares).
    const auto plain =
        CapturePlan::parse(ConfigNode::parse("frames_per_angle: 4\n", "plan.yaml")).to_json();
    EXPECT_FALSE(plain.contains("scene_reference"));
    EXPECT_FALSE(plain.contains("shutter_interleave"));
}

TEST(DriftReferencePlan, TheCaptureLoopClosesAndReopensTheShutterAndRecordsItsTemperature) {
    test::TempDir tmp;
    auto stage = make_simulated_stage("sim://", {});
    SimulatedCameraConfig config;
    config.width = 4;
    config.height = 4;
    config.frame_rate_hz = 500.0;
    SimulatedCamera camera(
        config, [](double, std::vector<float>& out) { std::fill(out.begin(), out.end(), 1000.0f); },
        simulated_stage_angle_source(*stage));
    const CapturePlan plan = CapturePlan::parse(ConfigNode::parse(kPlan, "plan.yaml"));
    auto session =
        SessionWriter::create(tmp / "s", new_session_manifest(camera.info(), stage->info(), plan));
    CaptureOptions options;
    options.progress_stream = nullptr;
    std::vector<std::string> prompts;  // the operator answers every prompt with "done"
    options.prompt = [&prompts](const std::string& text) { return prompts.push_back(text), true; };
    EXPECT_EQ(run_capture(camera, *stage, plan, session, options).steps_recorded, 11u);
    ASSERT_EQ(prompts.size(), 5u);  // close, open, close, open, close
    EXPECT_THAT(prompts[0], HasSubstr("Close the shutter"));
    EXPECT_THAT(prompts[1], HasSubstr("Open the shutter"));
    EXPECT_THAT(prompts[4], HasSubstr("Close the shutter"));
    const SessionManifest m = read_session(tmp / "s");
    int shutters = 0;
    for (const auto& r : m.records)
        if (r.kind == RecordKind::Shutter) {
            ++shutters;
            EXPECT_DOUBLE_EQ(r.blackbody_temperature_k.value_or(0.0), 295.0);
        }
    EXPECT_EQ(shutters, 3);
    EXPECT_EQ(m.plan["scene_reference"]["roi"]["x"], 1);
}

}  // namespace
}  // namespace tirpol::acquisition
