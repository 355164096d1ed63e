// `tirpol calibrate geometric|pose` as library calls (calibration::run_geometric_calibration,
// run_pose_estimation): the outputs are checked before anything is read, and target text of the
// wrong form is an OptionValueError naming --target (the CLI exits 2 with it). Full runs are in
// tests/apps/geometry_cli_test.cpp; the calibration itself in geometric_calibration_test.cpp.

#include <gtest/gtest.h>

#include "test_support.h"
#include "tirpol/calibration/geometric_calibration.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"

namespace tirpol::calibration {
namespace {

TEST(GeometryRun, TargetTextOfTheWrongFormNamesTarget) {
    tirpol::test::TempDir dir;
    GeometricRunOptions o;
    o.frames = {(dir / "missing.png").string()};
    o.output = (dir / "camera.yaml").string();
    for (const std::string target :
         {"checkerboard:9x6", "hexagons:9x6:0.02", "checkerboard:0x6:0.02"}) {
        o.target = target;
        try {
            run_geometric_calibration(o);
            ADD_FAILURE() << target << " accepted";
        } catch (const OptionValueError& e) {
            EXPECT_EQ(e.option(), "--target") << target;
        }
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "camera.yaml"));
}

TEST(GeometryRun, AnExistingOutputIsKeptUnlessForcedBeforeAnyInputIsRead) {
    tirpol::test::TempDir dir;
    tirpol::test::write_text(dir / "camera.yaml", "an earlier model");
    GeometricRunOptions geometric;
    geometric.frames = {(dir / "missing.png").string()};
    geometric.target = "checkerboard:9x6:0.02";
    geometric.output = (dir / "camera.yaml").string();
    EXPECT_THROW(run_geometric_calibration(geometric), OutputConflict);
    geometric.force = true;  // then the missing frame is the error, not the output
    try {
        run_geometric_calibration(geometric);
        ADD_FAILURE() << "no error for a missing frame";
    } catch (const OutputConflict& e) {
        ADD_FAILURE() << "refused although forced: " << e.what();
    } catch (const Error&) {
    }

    PoseRunOptions pose;
    pose.camera = (dir / "camera.yaml").string();
    pose.points = (dir / "points.csv").string();
    pose.output = (dir / "camera.yaml").string();  // the model it reads
    pose.force = true;
    EXPECT_THROW(run_pose_estimation(pose), OutputConflict);
}

}  // namespace
}  // namespace tirpol::calibration
