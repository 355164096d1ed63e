// `tirpol reduce` of a microgrid camera's session through the real executable: the session's
// recorded pattern is used without --calibration, the rotating-polarizer options are refused for it
// (exit 2), and --pixel-calibration is refused for a rotating-polarizer session.

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cli_runner.h"
#include "test_support.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/session.h"

namespace {

using namespace tirpol;
using ::testing::HasSubstr;
using tirpol::test::run_cli;

/// A session of a 8×6 microgrid camera in the Sony layout that recorded one mean frame of the
/// uniform scene S = (1000, −200, 300) (ideal analyzers: ½(S0 + S1 cos 2θ + S2 sin 2θ)).
void write_microgrid_session(const std::filesystem::path& dir) {
    SessionManifest m;
    m.camera = {"aravis://Aravis-Fake-GV01",
                "Aravis",
                "Fake",
                "GV01",
                "PolarizeMono16",
                8,
                6,
                16,
                30.0,
                {},
                std::array<double, 4>{90.0, 45.0, 135.0, 0.0}};
    m.stage = {"sim://", "tirpol", "SimStage", "S1", "1.0", 409600.0 / 3.0};
    Image frame(8, 6);
    auto& counts = frame.add_channel("counts");
    frame.add_channel("counts_std", 1.0f);
    const double angles[4] = {90.0, 45.0, 135.0, 0.0};
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 8; ++x) {
            const double theta = angles[(y & 1) * 2 + (x & 1)] * std::numbers::pi / 180.0;
            counts[frame.index(x, y)] = static_cast<float>(
                0.5 * (1000.0 - 200.0 * std::cos(2 * theta) + 300.0 * std::sin(2 * theta)));
        }
    SessionRecord r;
    r.file = session_frame_file("pol_000.0deg_r0");
    r.frames = 8;
    auto writer = SessionWriter::create(dir, m);
    writer.add_record(r, frame);
    writer.mark_complete();
}

TEST(MicrogridReduceCli, ReducesWithTheSessionsPatternWithoutACalibration) {
    test::TempDir dir;
    write_microgrid_session(dir / "s");
    const auto run = run_cli(fmt::format("reduce {} --method bilinear -o {}", (dir / "s").string(),
                                         (dir / "stokes.exr").string()));
    ASSERT_EQ(run.exit_code, 0) << run.out;
    EXPECT_THAT(run.out, HasSubstr("Stokes 8×6 (microgrid 90,45,135,0, bilinear, 8 frame(s))"));
    const Image stokes = read_exr(dir / "stokes.exr");
    EXPECT_NEAR(stokes.at("S0", 3, 2), 1000.0f, 1e-3);
    EXPECT_NEAR(stokes.at("S1", 3, 2), -200.0f, 1e-3);
    EXPECT_NEAR(stokes.at("S2", 3, 2), 300.0f, 1e-3);
    EXPECT_EQ(std::get<std::string>(stokes.attributes().at("demosaic_method")), "bilinear");
}

TEST(MicrogridReduceCli, RotatingPolarizerOptionsAndMicrogridOptionsAreRefusedOnTheOtherKind) {
    test::TempDir dir;
    write_microgrid_session(dir / "s");
    const std::string exr = (dir / "some.exr").string();
    Image some(2, 2);
    some.add_channel("counts", 1.0f);
    write_exr(exr, some);
    const auto with_calibration = run_cli(fmt::format(
        "reduce {} --calibration {} -o {}", (dir / "s").string(), exr, (dir / "o.exr").string()));
    EXPECT_EQ(with_calibration.exit_code, 2) << with_calibration.out;
    EXPECT_THAT(with_calibration.out,
                HasSubstr("--calibration is for a rotating-polarizer session"));
    const auto bad_method = run_cli(fmt::format("reduce {} --method cubic -o {}",
                                                (dir / "s").string(), (dir / "o.exr").string()));
    EXPECT_EQ(bad_method.exit_code, 2) << bad_method.out;
    EXPECT_THAT(bad_method.out, HasSubstr("--method"));

    SessionManifest plain;
    plain.camera = {"sim://", "tirpol", "SimCam", "1", "Mono16", 8, 6, 16, 30.0, {}, std::nullopt};
    plain.stage = {"sim://", "tirpol", "SimStage", "S1", "1.0", 409600.0 / 3.0};
    { auto writer = SessionWriter::create(dir / "plain", plain); }
    const auto pixel =
        run_cli(fmt::format("reduce {} --calibration {} --pixel-calibration {} -o {}",
                            (dir / "plain").string(), exr, exr, (dir / "o.exr").string()));
    EXPECT_EQ(pixel.exit_code, 2) << pixel.out;
    EXPECT_THAT(pixel.out, HasSubstr("--pixel-calibration is for microgrid sessions"));
}

}  // namespace
