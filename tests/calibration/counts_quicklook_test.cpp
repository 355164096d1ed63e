// The counts quick look of a session without calibration: S1 and S2 are the gain times the scene's
// (an offset common to the angles cancels), S0 keeps twice the offset, the read-back angles are
// used, σ follows W⁺ of the ideal four-angle analyzer, and it is labelled counts.

#include "counts_quicklook.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "test_support.h"
#include "tirpol/calibration/calibration_chain.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/session.h"

using namespace tirpol;
using ::testing::HasSubstr;

namespace {

constexpr int kW = 8, kH = 6;
constexpr double kGain = 100.0, kOffset = 5000.0, kS0 = 20.0, kS1 = 2.0, kS2 = -1.0;
constexpr double kCountsStd = 4.0;
constexpr int kFrames = 16;

SessionManifest manifest() {
    SessionManifest m;
    m.created_utc = "2026-11-27T05:00:00Z";
    m.camera = {"sim://quicklook", "tirpol", "test", "1", "Mono16", kW, kH, 16, 30.0, {}, {}};
    m.stage = {"sim://stage", "tirpol", "test", "1", "1", 1000.0};
    return m;
}

// Counts of the scene through an ideal polarizer at `angle_deg`: offset + gain·½(S0 + S1 cos 2α +
// S2 sin 2α), noiseless, with a stated frame scatter.
Image frame(double angle_deg, float counts_override = -1.0f) {
    const double a = 2.0 * angle_deg * std::numbers::pi / 180.0;
    const double counts = kOffset + kGain * 0.5 * (kS0 + kS1 * std::cos(a) + kS2 * std::sin(a));
    Image im(kW, kH);
    im.add_channel("counts",
                   counts_override >= 0.0f ? counts_override : static_cast<float>(counts));
    im.add_channel("counts_std", static_cast<float>(kCountsStd));
    return im;
}

SessionRecord record(const std::string& stem, double requested_deg, double measured_deg,
                     int repeat = 0) {
    SessionRecord r;
    r.kind = RecordKind::Polarizer;
    r.file = session_frame_file(stem);
    r.angle_deg_requested = requested_deg;
    r.angle_deg_measured = measured_deg;
    r.repeat = repeat;
    r.frames = kFrames;
    r.first_timestamp_ns = 1795359560000000000;
    r.last_timestamp_ns = r.first_timestamp_ns + 1000;
    return r;
}

// A scene session at 0/45/90/135° requested; the stage stood `stage_error_deg` further on.
void write_scene(const std::filesystem::path& dir, double stage_error_deg,
                 const std::vector<double>& angles = {0.0, 45.0, 90.0, 135.0}) {
    auto w = SessionWriter::create(dir, manifest());
    for (double a : angles)
        w.add_record(record("p" + std::to_string(static_cast<int>(a)), a, a + stage_error_deg),
                     frame(a + stage_error_deg));
    w.mark_complete();
}

}  // namespace

TEST(CountsQuicklook, RecoversTheGainTimesTheSceneStokesInCounts) {
    test::TempDir dir;
    write_scene(dir / "scene", 0.0);
    const Image s = calibration::reduce_session_counts(dir / "scene");
    EXPECT_NEAR(s.at("S0", 3, 2), 2.0 * kOffset + kGain * kS0, 1e-2);  // the offset stays in S0
    EXPECT_NEAR(s.at("S1", 3, 2), kGain * kS1, 1e-2);                  // and cancels in S1, S2
    EXPECT_NEAR(s.at("S2", 3, 2), kGain * kS2, 1e-2);
    EXPECT_NEAR(s.at("AoP", 3, 2), 0.5 * std::atan2(kS2, kS1) * 180.0 / std::numbers::pi + 180.0,
                1e-3);
    // σ of one record's mean σ_I = 4/√16 = 1 count; S0 = ½ΣI → σ_I, S1 = I0 − I90 → √2 σ_I.
    EXPECT_NEAR(s.at("S0_std", 3, 2), 1.0, 1e-4);
    EXPECT_NEAR(s.at("S1_std", 3, 2), std::sqrt(2.0), 1e-4);
    const auto& a = s.attributes();
    EXPECT_EQ(std::get<std::string>(a.at("units")), "counts");
    EXPECT_EQ(std::get<std::string>(a.at("units_S1")), "counts");
    EXPECT_THAT(std::get<std::string>(a.at("calibration")), HasSubstr("counts, not radiance"));
    EXPECT_EQ(a.count("calibration_range_k"), 0u) << "a counts image claims no calibration range";
}

TEST(CountsQuicklook, UsesTheAnglesTheStageReadBack) {
    // The stage stood 3° past each requested angle: reduced at the requested angles, S1 would leak
    // into S2 by sin 6° (≈ 0.1 S1); at the read-back angles the scene's S2 comes back.
    test::TempDir dir;
    write_scene(dir / "scene", 3.0);
    const Image s = calibration::reduce_session_counts(dir / "scene");
    EXPECT_NEAR(s.at("S1", 1, 1), kGain * kS1, 1e-2);
    EXPECT_NEAR(s.at("S2", 1, 1), kGain * kS2, 1e-2);
}

TEST(CountsQuicklook, KnownSourceRepeatsAreNotScene) {
    test::TempDir dir;
    {
        auto m = manifest();
        m.metadata = {{"known_source", {{{"repeat", 1}, {"stokes", {10.0, 10.0, 0.0}}}}}};
        auto w = SessionWriter::create(dir / "s", m);
        for (double a : {0.0, 45.0, 90.0, 135.0}) {
            const std::string stem = std::to_string(static_cast<int>(a));
            w.add_record(record("scene" + stem, a, a, 0), frame(a));
            w.add_record(record("source" + stem, a, a, 1), frame(a, 60000.0f));
        }
        w.mark_complete();
    }
    const Image s = calibration::reduce_session_counts(dir / "s");
    EXPECT_NEAR(s.at("S1", 0, 0), kGain * kS1, 1e-2);
}

TEST(CountsQuicklook, TooFewAnglesOrSaturationAreErrorsNamingTheFile) {
    test::TempDir dir;
    write_scene(dir / "two", 0.0, {0.0, 90.0});
    try {
        calibration::reduce_session_counts(dir / "two");
        FAIL() << "two angles reduced";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("session.json"));
        EXPECT_THAT(e.what(), HasSubstr("3 or more angles, got 2"));
    }
    {
        auto m = manifest();
        m.camera.bits_per_pixel = 14;  // saturates at 16383 counts
        auto w = SessionWriter::create(dir / "hot", m);
        for (double a : {0.0, 45.0, 90.0, 135.0})
            w.add_record(record("p" + std::to_string(static_cast<int>(a)), a, a),
                         frame(a, a == 90.0 ? 16383.0f : -1.0f));
        w.mark_complete();
    }
    try {
        calibration::reduce_session_counts(dir / "hot");
        FAIL() << "a saturated frame reduced";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("p90"));
        EXPECT_THAT(e.what(), HasSubstr("saturated"));
    }
}

// reduce_session without a calibration: the counts quick look written as EXR and labelled PNGs,
// summarised in counts with its label first.
TEST(CountsQuicklook, ReduceSessionWithoutCalibrationWritesAndLabelsTheQuickLook) {
    test::TempDir dir;
    write_scene(dir / "scene", 0.0);
    calibration::SessionToStokesOptions o;
    o.session = (dir / "scene").string();
    o.output = (dir / "stokes.exr").string();
    o.quicklooks = (dir / "looks").string();
    const calibration::SessionToStokes r = calibration::session_to_stokes(o);
    EXPECT_TRUE(r.counts_quicklook);
    EXPECT_NEAR(r.s0.mean, 2.0 * kOffset + kGain * kS0, 1e-2);
    EXPECT_EQ(r.saturated_pixels, 0);
    EXPECT_EQ(read_exr(o.output).width(), kW);
    for (const char* png : calibration::kStokesQuicklookFiles)
        EXPECT_TRUE(std::filesystem::exists(dir / "looks" / png)) << png;
    const std::string text = calibration::session_to_stokes_text(r);
    EXPECT_EQ(text.rfind(std::string(calibration::kCountsQuicklookLabel) + "\n", 0), 0u) << text;
    EXPECT_THAT(text, HasSubstr("Stokes 8×6 in counts: S0 mean 12000 counts"));
    EXPECT_THAT(text, HasSubstr("0 saturated → " + o.output + "\n"));
}
