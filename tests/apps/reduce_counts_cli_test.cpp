// `tirpol reduce SESSION -o OUT` without --calibration: a Stokes quick look in counts, labelled so
// in the EXR, the printed lines and the PNG titles; the calibration-only options are refused.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "cli_runner.h"
#include "test_support.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/session.h"

using namespace tirpol;
using ::testing::HasSubstr;
using tirpol::test::run_cli;

namespace {

// A 16×12 scene with S1 = 300 counts after the gain: counts = 5000 + ½(2000 + 300 cos 2α).
void write_scene(const std::filesystem::path& dir) {
    SessionManifest m;
    m.created_utc = "2026-11-27T05:00:00Z";
    m.camera = {"sim://quicklook", "tirpol", "test", "1", "Mono16", 16, 12, 16, 30.0, {}, {}};
    m.stage = {"sim://stage", "tirpol", "test", "1", "1", 1000.0};
    auto w = SessionWriter::create(dir, m);
    for (double a : {0.0, 45.0, 90.0, 135.0}) {
        SessionRecord r;
        r.kind = RecordKind::Polarizer;
        r.file = session_frame_file("p" + std::to_string(static_cast<int>(a)));
        r.angle_deg_requested = r.angle_deg_measured = a;
        r.frames = 4;
        r.first_timestamp_ns = 1795359560000000000;
        r.last_timestamp_ns = r.first_timestamp_ns + 1000;
        Image im(16, 12);
        im.add_channel("counts", static_cast<float>(
                                     5000.0 + 0.5 * (2000.0 + 300.0 * std::cos(a * M_PI / 90.0))));
        im.add_channel("counts_std", 3.0f);
        w.add_record(r, im);
    }
    w.mark_complete();
}

}  // namespace

TEST(ReduceCountsCli, WithoutCalibrationWritesALabelledCountsQuickLook) {
    test::TempDir dir;
    write_scene(dir / "scene");
    const auto out = dir / "quick.exr";
    const auto pngs = dir / "png";
    const auto r = run_cli("reduce " + (dir / "scene").string() + " -o " + out.string() +
                           " --quicklooks " + pngs.string());
    ASSERT_EQ(r.exit_code, 0) << r.out;
    EXPECT_THAT(r.out, HasSubstr("counts quick look: no radiometric or polarimetric calibration "
                                 "applied; counts, not radiance"));
    EXPECT_THAT(r.out, HasSubstr("in counts: S0 mean 12000 counts"));
    const Image s = read_exr(out);
    EXPECT_NEAR(s.at("S1", 4, 4), 300.0, 1e-2);
    EXPECT_NEAR(s.at("DoLP", 4, 4), 300.0 / 12000.0, 1e-5);
    EXPECT_EQ(std::get<std::string>(s.attributes().at("units")), "counts");
    EXPECT_THAT(std::get<std::string>(s.attributes().at("calibration")),
                HasSubstr("counts, not radiance"));
    for (const char* c : {"S0", "S1", "S2", "DoLP", "AoP"})
        EXPECT_TRUE(std::filesystem::is_regular_file(pngs / (std::string(c) + ".png"))) << c;
}

TEST(ReduceCountsCli, CalibrationOnlyOptionsNeedACalibration) {
    test::TempDir dir;
    write_scene(dir / "scene");
    for (const char* option :
         {"--slar", "--update-offset", "--drift-correction", "--other-camera"}) {
        const auto r = run_cli("reduce " + (dir / "scene").string() + " -o " +
                               (dir / "q.exr").string() + " " + option);
        EXPECT_EQ(r.exit_code, 2) << option << "\n" << r.out;
        EXPECT_THAT(r.out, HasSubstr(std::string(option) + " needs --calibration")) << option;
        EXPECT_FALSE(std::filesystem::exists(dir / "q.exr")) << option;
    }
}
