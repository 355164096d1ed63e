// What `tirpol live` checks before it opens a device: a bad option value is a usage error naming
// the option (OptionValueError), and the snapshot folder never takes an input's place or, unless
// forced, an existing snapshot; it is created when it passes.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "test_support.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/live/live_server.h"

namespace tirpol::live {
namespace {

using ::testing::HasSubstr;

std::string refused_option(const LiveViewOptions& view, const ServerOptions& server) {
    try {
        check_live_run(view, server);
    } catch (const OptionValueError& e) {
        EXPECT_THAT(e.what(), HasSubstr(e.option()));
        return e.option();
    }
    return "";
}

TEST(LiveRunCheck, AnOptionValueOutOfRangeIsRefusedNamingTheOption) {
    LiveViewOptions view;
    view.camera_uri = "sim://";
    ServerOptions server;
    EXPECT_EQ(refused_option(view, server), "");
    view.cycle.settle_s = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(refused_option(view, server), "--settle-s");
    view.cycle.settle_s = 0.2;
    view.demosaic = "cubic";
    EXPECT_EQ(refused_option(view, server), "--demosaic");
    view.demosaic = "newton";
    server.port = 70000;
    EXPECT_EQ(refused_option(view, server), "--port");
    server.port = 0;
    view.camera_uri.clear();
    EXPECT_EQ(refused_option(view, server), "--camera");
}

TEST(LiveRunCheck, TheSnapshotFolderIsCheckedAgainstInputsAndCreated) {
    test::TempDir dir;
    LiveViewOptions view;
    view.camera_uri = "sim://";
    view.snapshot_dir = (dir / "snaps").string();
    check_live_run(view, {});
    EXPECT_TRUE(std::filesystem::is_directory(view.snapshot_dir));

    // An input under a name the snapshots take would be replaced by one, even with force.
    view.calibration_path = (dir / "snaps" / "snapshot-cal.exr").string();
    std::ofstream(view.calibration_path) << "calibration";
    view.force_snapshots = true;
    EXPECT_THROW(check_live_run(view, {}), OutputConflict);

    // A snapshot no tirpol command wrote there is replaced only with force.
    std::filesystem::rename(view.calibration_path, dir / "cal.exr");
    view.calibration_path = (dir / "cal.exr").string();
    std::ofstream(dir / "snaps" / "snapshot-0001.exr") << "earlier";
    view.force_snapshots = false;
    EXPECT_THROW(check_live_run(view, {}), OutputConflict);
    view.force_snapshots = true;
    EXPECT_NO_THROW(check_live_run(view, {}));
}

}  // namespace
}  // namespace tirpol::live
