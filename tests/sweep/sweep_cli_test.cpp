// `tirpol sweep` as a user runs it: a failing point is listed and the exit code is 1 once the other
// points are done; a bad sweep file is exit code 1 with file:line and a suggestion (docs/cli.md).

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "../apps/cli_runner.h"
#include "sweep_test_support.h"

namespace tirpol::sweep {
namespace {

using tirpol::test::run_cli;

TEST(SweepCli, FailingPointIsListedAndTheExitCodeIsOneAfterTheOthers) {
    tirpol::test::TempDir dir;
    const auto sweep = test::write_small_sweep(
        dir, "axes:\n  band: [{lo_um: 8, hi_um: 14}, {lo_um: 14, hi_um: 8}]\n");
    const auto r =
        run_cli(fmt::format("sweep {} -o {} -q", sweep.string(), (dir / "out").string()));
    EXPECT_EQ(r.exit_code, 1) << r.out;
    EXPECT_NE(r.out.find("1 rendered, 0 resumed, 1 failed"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("FAILED p0001: "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("1 of 2 points failed"), std::string::npos) << r.out;
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "out/points/p0000/stokes.exr"));
}

TEST(SweepCli, UnknownParameterIsExitCodeOneWithASuggestion) {
    tirpol::test::TempDir dir;
    const auto sweep = test::write_small_sweep(dir, "axes:\n  camera.fov_dge: [20, 30]\n");
    const auto r = run_cli(fmt::format("sweep {} -o {}", sweep.string(), (dir / "out").string()));
    EXPECT_EQ(r.exit_code, 1) << r.out;
    EXPECT_NE(r.out.find("sweep.yaml:6:"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("did you mean 'fov_deg'?"), std::string::npos) << r.out;
    EXPECT_FALSE(std::filesystem::exists(dir / "out")) << "nothing is written for a bad sweep file";
}

}  // namespace
}  // namespace tirpol::sweep
