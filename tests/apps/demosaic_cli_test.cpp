// `tirpol demosaic` end to end through the real executable: a microgrid EXR frame → Stokes EXR, the
// pattern from the header or the command line, and exit codes for bad usage (2) and bad input (1).

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cli_runner.h"
#include "test_support.h"
#include "tirpol/core/exr_io.h"

namespace {

using namespace tirpol;
using tirpol::test::run_cli;

// A uniform scene S = (1000, −200, 300) seen through ideal analyzers of the Sony IMX250MZR layout
// (0,0) = 90°, (0,1) = 45°, (1,0) = 135°, (1,1) = 0°: each pixel ½(S0 + S1 cos 2θ + S2 sin 2θ).
Image sony_frame(bool record_pattern) {
    const double angles[4] = {90.0, 45.0, 135.0, 0.0};
    Image im(8, 6);
    auto& counts = im.add_channel("counts");
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 8; ++x) {
            const double theta = angles[(y & 1) * 2 + (x & 1)] * std::numbers::pi / 180.0;
            counts[im.index(x, y)] = static_cast<float>(
                0.5 * (1000.0 - 200.0 * std::cos(2 * theta) + 300.0 * std::sin(2 * theta)));
        }
    if (record_pattern)
        im.attributes()["microgrid_pattern_deg"] = std::vector<double>{90.0, 45.0, 135.0, 0.0};
    return im;
}

TEST(DemosaicCli, WritesStokesWithTheRecordedPatternAndMethod) {
    test::TempDir dir;
    write_exr(dir / "frame.exr", sony_frame(true));
    const auto run =
        run_cli(fmt::format("demosaic {} --method newton -o {}", (dir / "frame.exr").string(),
                            (dir / "stokes.exr").string()));
    ASSERT_EQ(run.exit_code, 0) << run.out;
    EXPECT_NE(run.out.find("Stokes 8×6 (newton, pattern 90,45,135,0)"), std::string::npos)
        << run.out;
    const Image stokes = read_exr(dir / "stokes.exr");
    EXPECT_NEAR(stokes.at("S0", 3, 2), 1000.0f, 1e-3);
    EXPECT_NEAR(stokes.at("S1", 3, 2), -200.0f, 1e-3);
    EXPECT_NEAR(stokes.at("S2", 3, 2), 300.0f, 1e-3);
    EXPECT_EQ(std::get<std::string>(stokes.attributes().at("demosaic_method")), "newton");
    EXPECT_EQ(std::get<std::string>(stokes.attributes().at("microgrid_pattern")), "90,45,135,0");
}

TEST(DemosaicCli, SuperPixelHalvesTheSizeAndTheCommandLinePatternServesAFileWithoutOne) {
    test::TempDir dir;
    write_exr(dir / "frame.exr", sony_frame(false));
    const auto run =
        run_cli(fmt::format("demosaic {} --pattern sony --method super-pixel -o {}",
                            (dir / "frame.exr").string(), (dir / "stokes.exr").string()));
    ASSERT_EQ(run.exit_code, 0) << run.out;
    const Image stokes = read_exr(dir / "stokes.exr");
    EXPECT_EQ(stokes.width(), 4);
    EXPECT_EQ(stokes.height(), 3);
    EXPECT_NEAR(stokes.at("S1", 1, 1), -200.0f, 1e-3);
}

TEST(DemosaicCli, BadUsageExits2AndBadInputExits1NamingTheProblem) {
    test::TempDir dir;
    write_exr(dir / "frame.exr", sony_frame(false));
    const std::string in = (dir / "frame.exr").string(), out = (dir / "stokes.exr").string();
    auto run = run_cli(fmt::format("demosaic {} --pattern 0,45,90,45 -o {}", in, out));
    EXPECT_EQ(run.exit_code, 2) << run.out;
    EXPECT_NE(run.out.find("--pattern"), std::string::npos) << run.out;
    run = run_cli(fmt::format("demosaic {} --pattern sony --method cubic -o {}", in, out));
    EXPECT_EQ(run.exit_code, 2) << run.out;
    EXPECT_NE(run.out.find("cubic"), std::string::npos) << run.out;
    run = run_cli(fmt::format("demosaic {} -o {}", in, out));
    EXPECT_EQ(run.exit_code, 1) << run.out;
    EXPECT_NE(run.out.find("no microgrid pattern given"), std::string::npos) << run.out;
    EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
