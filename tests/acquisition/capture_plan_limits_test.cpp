// Capture-plan validation: a plan that would start a run that never
// ends, or that does not say what the user meant, is refused before any device moves, with a
// message naming the file, the field and the accepted range.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_support.h"
#include "tirpol/acquisition/capture_plan.h"
#include "tirpol/core/error.h"

namespace tirpol::acquisition {
namespace {

using ::testing::HasSubstr;

std::string error_of(const std::string& yaml) {
    try {
        CapturePlan::parse(ConfigNode::parse(yaml, "plan.yaml"));
    } catch (const Error& e) {
        return e.what();
    }
    return "(accepted)";
}

TEST(CapturePlanLimits, AnEmptyPlanFileIsAnErrorNotTheDefaultPlan) {
    test::TempDir tmp;
    for (const char* text : {"", "# only a comment\n", "{}\n"}) {
        test::write_text(tmp / "plan.yaml", text);
        try {
            CapturePlan::load(tmp / "plan.yaml");
            ADD_FAILURE() << "accepted the plan file \"" << text << "\"";
        } catch (const Error& e) {
            EXPECT_THAT(e.what(), HasSubstr("plan.yaml"));
            EXPECT_THAT(e.what(), HasSubstr("capture plan is empty"));
        }
    }
    // One field is enough: the rest take their documented defaults.
    test::write_text(tmp / "plan.yaml", "frames_per_angle: 3\n");
    const CapturePlan plan = CapturePlan::load(tmp / "plan.yaml");
    EXPECT_EQ(plan.frames_per_angle, 3);
    EXPECT_EQ(plan.angles_deg, (std::vector<double>{0, 45, 90, 135}));
}

TEST(CapturePlanLimits, AnglesOutsideZeroTo360AreRefusedNotWrapped) {
    EXPECT_THAT(error_of("angles_deg: [0, 45, 405]"),
                HasSubstr("angle 405° is outside [0, 360) (the same position is 45°)"));
    EXPECT_THAT(error_of("angles_deg: [-45, 0]"),
                HasSubstr("angle -45° is outside [0, 360) (the same position is 315°)"));
    EXPECT_THAT(error_of("angles_deg: [0, 360]"), HasSubstr("angles_deg"));
    EXPECT_THAT(error_of("angles_deg: [0, .nan]"), HasSubstr("angles_deg[1]"));
    EXPECT_THAT(error_of("references: [{kind: shutter, angle_deg: 370}]"),
                HasSubstr("references[0].angle_deg"));
    // The edges of the range are positions like any other.
    const CapturePlan plan =
        CapturePlan::parse(ConfigNode::parse("angles_deg: [0, 359.999]", "plan.yaml"));
    EXPECT_EQ(plan.angles_deg, (std::vector<double>{0, 359.999}));
}

TEST(CapturePlanLimits, ValuesThatWouldRunForeverAreRefusedBeforeAnythingStarts) {
    // The two reported cases: a settle time of 2^32 s and 2^31 − 1 frames per angle.
    EXPECT_THAT(error_of("settle_s: 4294967296"),
                HasSubstr("settle_s: expected a duration in seconds ≥ 0 and ≤ 3600"));
    EXPECT_THAT(
        error_of("frames_per_angle: 0x7fffffff"),
        HasSubstr("frames_per_angle: expected an integer ≥ 1 and ≤ 100000, got 2147483647"));
    EXPECT_THAT(error_of("repeats: 10001"),
                HasSubstr("repeats: expected an integer ≥ 1 and ≤ 10000"));
    EXPECT_THAT(error_of("move_timeout_s: 3601"), HasSubstr("move_timeout_s"));
    EXPECT_THAT(error_of("home_timeout_s: 1e9"), HasSubstr("home_timeout_s"));
    EXPECT_THAT(error_of("frame_timeout_s: 601"), HasSubstr("frame_timeout_s"));
    EXPECT_THAT(error_of("frame_timeout_s: .inf"), HasSubstr("frame_timeout_s"));
    EXPECT_THAT(error_of("references: [{kind: shutter, frames: 100001}]"),
                HasSubstr("references[0].frames"));
    // The limits themselves are accepted.
    const CapturePlan plan =
        CapturePlan::parse(ConfigNode::parse("settle_s: 3600\nframes_per_angle: 100000\nrepeats: "
                                             "10000\nmove_timeout_s: 3600\nframe_timeout_s: 600\n",
                                             "plan.yaml"));
    EXPECT_EQ(plan.settle_s, kMaxSettleSeconds);
    EXPECT_EQ(plan.frames_per_angle, kMaxFramesPerStep);
    EXPECT_EQ(plan.repeats, kMaxRepeats);
}

TEST(CapturePlanLimits, ErrorsNameTheFileAndLine) {
    EXPECT_THAT(error_of("frames_per_angle: 4\nsettle_s: 99999\n"), HasSubstr("plan.yaml:2"));
}

TEST(CapturePlanLimits, BadDriftReferencesAreReportedByField) {
    EXPECT_THAT(error_of("scene_reference: {roi: {x: 1, y: 1, width: 2, height: 2}}"),
                HasSubstr("contact-sensor"));
    EXPECT_THAT(
        error_of("scene_reference: {roi: {x: 1, y: 1, width: 0, height: 2}, temperature_k: 300}"),
        HasSubstr("width"));
    EXPECT_THAT(
        error_of("scene_reference: {roi: {x: 1.5, y: 1, width: 2, height: 2}, temperature_k: 300}"),
        HasSubstr("whole number"));
    EXPECT_THAT(error_of("shutter_interleave: {every: 0}"), HasSubstr("every"));
    EXPECT_THAT(error_of("shutter_interleave: {every: 2, temperature_k: 295, temperature_c: 20}"),
                HasSubstr("not both"));
    EXPECT_THAT(error_of("shutter_interleave: {evry: 2}"), HasSubstr("evry"));
}

}  // namespace
}  // namespace tirpol::acquisition
