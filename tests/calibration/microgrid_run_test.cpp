// What `tirpol demosaic`, `tirpol reduce` of a microgrid session and `tirpol calibrate microgrid`
// run, as library calls: the typed summaries carry the planted Stokes values, the pattern and the
// units of what was written; option text that names nothing is refused naming its option before
// any file is read; outputs never replace inputs, and existing files only with `force`.

#include "tirpol/calibration/microgrid_run.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "test_support.h"
#include "tirpol/calibration/synthetic_session.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/core/session.h"

namespace tirpol::calibration {
namespace {

using ::testing::HasSubstr;

constexpr int kWidth = 16, kHeight = 12;

// A uniform field S = (1000, −200, 300) counts through ideal analyzers in the Sony layout, written
// as an EXR frame that records no pattern.
std::filesystem::path write_frame(const std::filesystem::path& dir) {
    const std::vector<float> s0(kWidth * kHeight, 1000.0f), s1(kWidth * kHeight, -200.0f),
        s2(kWidth * kHeight, 300.0f);
    Image frame(kWidth, kHeight);
    frame.set_channel("counts", microgrid_from_stokes(s0, s1, s2, kWidth, kHeight,
                                                      MicrogridPattern::sony_imx250mzr()));
    write_exr(dir / "frame.exr", frame);
    return dir / "frame.exr";
}

TEST(MicrogridRun, DemosaicRunReportsThePlantedStokesAndThePatternItUsed) {
    test::TempDir dir;
    DemosaicRunOptions o;
    o.input = write_frame(dir.path()).string();
    o.output = (dir / "stokes.exr").string();
    o.pattern = "sony";
    o.method = "bilinear";
    const DemosaicRun run = run_demosaic(o);
    EXPECT_EQ(run.width, kWidth);
    EXPECT_EQ(run.height, kHeight);
    EXPECT_EQ(run.method, DemosaicMethod::Bilinear);
    EXPECT_EQ(run.pattern, "90,45,135,0");
    EXPECT_EQ(run.units, "counts");
    EXPECT_NEAR(run.s0_mean, 1000.0, 1e-3);
    EXPECT_NEAR(run.dolp_mean, std::hypot(200.0, 300.0) / 1000.0, 1e-6);
    EXPECT_EQ(run.unrealizable_pixels, 0);
    const Image written = read_exr(o.output);
    EXPECT_NEAR(written.at("S1", 3, 2), -200.0f, 1e-3);
    EXPECT_THAT(demosaic_run_text(run),
                HasSubstr("Stokes 16×12 (bilinear, pattern 90,45,135,0): S0 mean 1000 counts, "
                          "DoLP mean 0.3606; 0 unrealizable pixel(s) projected → " +
                          o.output));
}

TEST(MicrogridRun, OptionTextThatNamesNothingIsRefusedNamingTheOptionBeforeAnyOutput) {
    test::TempDir dir;
    DemosaicRunOptions o;
    o.input = write_frame(dir.path()).string();
    o.output = (dir / "stokes.exr").string();
    o.method = "cubic";
    try {
        run_demosaic(o);
        FAIL() << "an unknown method was accepted";
    } catch (const OptionValueError& e) {
        EXPECT_EQ(e.option(), "--method");
        EXPECT_THAT(e.what(), HasSubstr("cubic"));
    }
    o.method = "newton";
    o.pattern = "0,45,90";  // three angles
    try {
        run_demosaic(o);
        FAIL() << "a three-angle pattern was accepted";
    } catch (const OptionValueError& e) {
        EXPECT_EQ(e.option(), "--pattern");
    }
    EXPECT_FALSE(std::filesystem::exists(o.output));

    MicrogridReduceRunOptions r;
    r.session = (dir / "session").string();
    r.output = (dir / "reduced.exr").string();
    r.method = "cubic";
    EXPECT_THROW(run_microgrid_reduction(r), OptionValueError);

    MicrogridCalibrationRunOptions c;
    c.sessions = {(dir / "flat").string()};
    c.output = (dir / "cal.exr").string();
    c.band_um = {14.0, 8.0};
    try {
        run_microgrid_calibration(c);
        FAIL() << "a band with LO > HI was accepted";
    } catch (const OptionValueError& e) {
        EXPECT_EQ(e.option(), "--band-um");
        EXPECT_THAT(e.what(), HasSubstr("expected 0 < LO < HI"));
    }
    EXPECT_FALSE(std::filesystem::exists(c.output));
}

TEST(MicrogridRun, OutputsNeverReplaceInputsAndReplaceExistingFilesOnlyWithForce) {
    test::TempDir dir;
    DemosaicRunOptions o;
    o.input = write_frame(dir.path()).string();
    o.pattern = "sony";
    o.output = o.input;
    o.force = true;
    EXPECT_THROW(run_demosaic(o), OutputConflict);
    o.output = (dir / "existing.exr").string();
    std::ofstream(o.output) << "not an EXR";
    o.force = false;
    EXPECT_THROW(run_demosaic(o), OutputConflict);
    o.force = true;
    EXPECT_EQ(run_demosaic(o).width, kWidth);
    EXPECT_TRUE(read_exr(o.output).has_channel("DoLP"));
}

TEST(MicrogridRun, CalibrationAndReductionOfSessionsReportInTheUnitsTheyWrite) {
    test::TempDir dir;
    SyntheticMicrogridCamera camera;
    camera.width = 32;
    camera.height = 24;
    camera.dead_x = 3;
    camera.dead_y = 3;
    const Band band(8.0, 14.0);
    write_synthetic_microgrid_flat_field(dir / "flat", camera, band);
    const double s0 = band.radiance(300.0), dolp = 0.3;
    write_synthetic_microgrid_scene(
        dir / "scene", camera,
        uniform_stokes_scene(camera, {s0, s0 * dolp * std::cos(std::numbers::pi / 3),
                                      s0 * dolp * std::sin(std::numbers::pi / 3)}));
    EXPECT_TRUE(is_readable_microgrid_session(dir / "scene"));
    EXPECT_FALSE(is_readable_microgrid_session(dir.path()));  // no manifest
    std::filesystem::create_directories(dir / "damaged");
    std::ofstream(dir / "damaged" / kSessionManifestName) << "{ not json";
    EXPECT_FALSE(is_readable_microgrid_session(dir / "damaged"));

    MicrogridCalibrationRunOptions c;
    c.sessions = {(dir / "flat").string()};
    c.output = (dir / "pixcal.exr").string();
    const MicrogridCalibrationRun cal = run_microgrid_calibration(c);
    EXPECT_EQ(cal.calibration.open_blackbody_records, 2u);
    EXPECT_EQ(cal.calibration.bad_count(kDead), 1u);
    EXPECT_THAT(microgrid_calibration_text(cal),
                HasSubstr("microgrid calibration 32×24 from 2 open-blackbody and 16 polarizer"));
    const Image written = read_exr(c.output);
    // Two reals, as every other image's band (read_stokes_image_header reads it).
    EXPECT_EQ(std::get<std::vector<double>>(written.attributes().at("band_um")),
              (std::vector<double>{8.0, 14.0}));
    EXPECT_EQ(read_stokes_image_header(written, c.output).band_um, (std::array{8.0, 14.0}));

    MicrogridReduceRunOptions r;
    r.session = (dir / "scene").string();
    r.output = (dir / "stokes.exr").string();
    r.quicklooks = (dir / "looks").string();
    r.pixel_calibration = c.output;
    const MicrogridReduceRun calibrated = run_microgrid_reduction(r);
    EXPECT_EQ(calibrated.reduction, "per-pixel calibration");
    EXPECT_EQ(calibrated.units, "W/(m^2 sr)");
    EXPECT_EQ(calibrated.pattern, "90,45,135,0");
    EXPECT_EQ(calibrated.frames_averaged, camera.frames);
    EXPECT_NEAR(calibrated.s0_mean, s0, 0.002 * s0);
    EXPECT_NEAR(calibrated.dolp_mean, dolp, 0.002);
    for (const char* png : {"S0.png", "S1.png", "S2.png", "DoLP.png", "AoP.png"})
        EXPECT_TRUE(std::filesystem::exists(dir / "looks" / png)) << png;
    EXPECT_EQ(std::get<std::string>(read_exr(r.output).attributes().at("pixel_calibration")),
              c.output);
    EXPECT_THAT(microgrid_reduce_run_text(calibrated),
                HasSubstr("(microgrid 90,45,135,0, per-pixel calibration, 16 frame(s))"));

    r.pixel_calibration.clear();
    r.quicklooks.clear();
    r.method = "super-pixel";
    r.force = true;
    const MicrogridReduceRun counts = run_microgrid_reduction(r);
    EXPECT_EQ(counts.reduction, "super-pixel");
    EXPECT_EQ(counts.units, "counts");
    EXPECT_EQ(counts.width, camera.width / 2);
}

}  // namespace
}  // namespace tirpol::calibration
