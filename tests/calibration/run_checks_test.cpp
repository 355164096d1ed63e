// What `tirpol reduce` and `tirpol calibrate radiometric|polarimetric` check before any work
// (calibration::check_session_to_stokes, check_radiometric_run, check_polarimetric_run): options
// that need another are refused with an OptionValueError naming the option (the CLI exits 2 with
// it), an existing output is kept unless forced, and an input is never replaced.

#include <gtest/gtest.h>

#include "test_support.h"
#include "tirpol/calibration/calibration_chain.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"

namespace tirpol::calibration {
namespace {

TEST(SessionToStokesCheck, CalibratedSwitchesWithoutACalibrationNameTheSwitch) {
    tirpol::test::TempDir dir;
    std::filesystem::create_directories(dir / "session");
    SessionToStokesOptions base;
    base.session = (dir / "session").string();
    base.output = (dir / "stokes.exr").string();
    EXPECT_NO_THROW(check_session_to_stokes(base, false));
    const std::pair<const char*, void (*)(SessionToStokesOptions&)> cases[] = {
        {"--polarimetric", [](SessionToStokesOptions& o) { o.polarimetric = "pol.yaml"; }},
        {"--update-offset", [](SessionToStokesOptions& o) { o.update_offset = true; }},
        {"--drift-correction", [](SessionToStokesOptions& o) { o.drift_correction = true; }},
        {"--slar", [](SessionToStokesOptions& o) { o.slar = true; }},
        {"--other-camera", [](SessionToStokesOptions& o) { o.other_camera = true; }},
    };
    for (const auto& [option, set] : cases) {
        SessionToStokesOptions o = base;
        set(o);
        try {
            check_session_to_stokes(o, false);
            ADD_FAILURE() << option << " accepted without --calibration";
        } catch (const OptionValueError& e) {
            EXPECT_EQ(e.option(), option);
            EXPECT_NE(std::string(e.what()).find("needs --calibration"), std::string::npos);
        }
    }
}

TEST(SessionToStokesCheck, AnExistingOutputIsKeptUnlessForcedAndAnInputNeverReplaced) {
    tirpol::test::TempDir dir;
    std::filesystem::create_directories(dir / "session");
    tirpol::test::write_text(dir / "stokes.exr", "an earlier result");
    tirpol::test::write_text(dir / "cal.exr", "a calibration");
    SessionToStokesOptions o;
    o.session = (dir / "session").string();
    o.calibration = (dir / "cal.exr").string();
    o.output = (dir / "stokes.exr").string();
    EXPECT_THROW(check_session_to_stokes(o, false), OutputConflict);
    EXPECT_NO_THROW(check_session_to_stokes(o, true));
    o.output = o.calibration;
    EXPECT_THROW(check_session_to_stokes(o, true), OutputConflict);
}

TEST(CalibrationRunCheck, RadiometricSummaryFolderIsKeptUnlessForced) {
    tirpol::test::TempDir dir;
    std::filesystem::create_directories(dir / "session");
    std::filesystem::create_directories(dir / "summary");
    tirpol::test::write_text(dir / "summary" / "index.html", "another page");
    RadiometricRunOptions o;
    o.sessions = {(dir / "session").string()};
    o.output = (dir / "cal.exr").string();
    o.summary = (dir / "summary").string();
    EXPECT_THROW(check_radiometric_run(o, false), OutputConflict);
    EXPECT_NO_THROW(check_radiometric_run(o, true));
    o.output = (dir / "session").string();  // a session is an input
    EXPECT_THROW(check_radiometric_run(o, true), OutputConflict);
}

TEST(CalibrationRunCheck, PolarimetricAxisOffsetsNeedTheExtinctionRatio) {
    tirpol::test::TempDir dir;
    std::filesystem::create_directories(dir / "session");
    PolarimetricRunOptions o;
    o.session = (dir / "session").string();
    o.output = (dir / "pol.yaml").string();
    o.axis_offsets_deg = {0.5};
    try {
        check_polarimetric_run(o, false);
        ADD_FAILURE() << "axis offsets accepted without an extinction ratio";
    } catch (const OptionValueError& e) {
        EXPECT_EQ(e.option(), "--axis-offset-deg");
    }
    o.extinction_ratio = 300.0;
    EXPECT_NO_THROW(check_polarimetric_run(o, false));
    // The maps beside the YAML are an output too.
    tirpol::test::write_text(polarimetric_maps_path(o.output), "earlier maps");
    EXPECT_THROW(check_polarimetric_run(o, false), OutputConflict);
}

}  // namespace
}  // namespace tirpol::calibration
