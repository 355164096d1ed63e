// A microgrid camera's capture session (session v5 records its 2×2 pattern) → Stokes: the records'
// mosaics are averaged by frame count and reduced with the recorded pattern, or per super-pixel
// with a per-pixel analyzer calibration; sessions that are not a microgrid camera's, or hold
// nothing to reduce, are refused naming the manifest.

#include "tirpol/calibration/microgrid_session.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "test_support.h"
#include "tirpol/calibration/microgrid_stokes.h"
#include "tirpol/core/error.h"
#include "tirpol/core/session.h"

namespace tirpol::calibration {
namespace {

using ::testing::HasSubstr;

constexpr int kWidth = 16, kHeight = 12;

SessionManifest manifest(std::optional<std::array<double, 4>> pattern) {
    SessionManifest m;
    m.camera = {"aravis://Aravis-Fake-GV01",
                "Aravis",
                "Fake",
                "GV01",
                "PolarizeMono12",
                kWidth,
                kHeight,
                12,
                30.0,
                {},
                pattern};
    m.stage = {"sim://", "tirpol", "SimStage", "S1", "1.0", 409600.0 / 3.0};
    return m;
}

SessionRecord record(int repeat, std::int64_t frames) {
    SessionRecord r;
    r.kind = RecordKind::Polarizer;
    r.file = session_frame_file(fmt::format("pol_000.0deg_r{}", repeat));
    r.repeat = repeat;
    r.frames = frames;
    r.first_timestamp_ns = 1795359560123456789;
    r.last_timestamp_ns = 1795359560623456789;
    return r;
}

Image frame(const std::vector<float>& mosaic) {
    Image image(kWidth, kHeight);
    image.set_channel("counts", mosaic);
    image.add_channel("counts_std", 1.0f);
    return image;
}

/// The mosaic of a uniform field (S0, S1, S2) through ideal analyzers in `pattern`.
std::vector<float> uniform_mosaic(double s0, double s1, double s2,
                                  const MicrogridPattern& pattern) {
    const std::vector<float> p0(kWidth * kHeight, static_cast<float>(s0)),
        p1(kWidth * kHeight, static_cast<float>(s1)), p2(kWidth * kHeight, static_cast<float>(s2));
    return microgrid_from_stokes(p0, p1, p2, kWidth, kHeight, pattern);
}

TEST(MicrogridSession, AveragesRecordsByFrameCountAndReducesWithTheRecordedPattern) {
    // A non-Sony layout recorded in the session: reducing with any other pattern mixes S1 and S2.
    const MicrogridPattern pattern({0.0, 45.0, 135.0, 90.0});
    test::TempDir tmp;
    {
        auto writer = SessionWriter::create(tmp / "s", manifest(pattern.angles_deg()));
        // 3 frames of S = (1000, 200, −100) and 1 frame of (1400, 600, 300): the frame-weighted
        // mean is (1100, 300, 0); a plain mean of the records would give (1200, 400, 100).
        writer.add_record(record(0, 3), frame(uniform_mosaic(1000.0, 200.0, -100.0, pattern)));
        writer.add_record(record(1, 1), frame(uniform_mosaic(1400.0, 600.0, 300.0, pattern)));
        writer.mark_complete();
    }
    EXPECT_TRUE(is_microgrid_session(tmp / "s"));
    for (DemosaicMethod method :
         {DemosaicMethod::SuperPixel, DemosaicMethod::Bilinear, DemosaicMethod::Newton}) {
        MicrogridSessionOptions options;
        options.method = method;
        const Image stokes = reduce_microgrid_session(tmp / "s", options);
        const MicrogridSessionRecord recorded = microgrid_session_record(stokes);
        EXPECT_EQ(recorded.frames_averaged, 4);
        EXPECT_EQ(recorded.records_averaged, 2);
        EXPECT_EQ(recorded.pattern.text(), "0,45,135,90");
        EXPECT_EQ(recorded.units, "counts");
        for (std::size_t i = 0; i < stokes.pixel_count(); ++i) {
            ASSERT_NEAR(stokes.channel("S0")[i], 1100.0, 1e-2);
            ASSERT_NEAR(stokes.channel("S1")[i], 300.0, 1e-2);
            ASSERT_NEAR(stokes.channel("S2")[i], 0.0, 1e-2);
        }
    }
}

TEST(MicrogridSession, PerPixelCalibrationReducesPerSuperPixelWithEachPixelsAnalyzer) {
    const MicrogridPattern sony = MicrogridPattern::sony_imx250mzr();
    // Planted: every pixel's analyzer is ideal except a 0.8 transmission on the 0° pixels. Ideal
    // reduction then reads a false S1; the calibration that knows it does not.
    MicrogridPixelCalibration c;
    c.width = kWidth;
    c.height = kHeight;
    for (auto& plane : c.analysis) plane.assign(kWidth * kHeight, 0.0f);
    c.background.assign(kWidth * kHeight, 0.0f);
    std::vector<float> mosaic(kWidth * kHeight);
    const double s[3] = {1000.0, 0.0, 250.0};
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const std::size_t i = static_cast<std::size_t>(y * kWidth + x);
            const double theta = sony.angle_at_pixel_deg(x, y) * std::numbers::pi / 180.0;
            const double t = sony.angle_at_pixel_deg(x, y) == 0.0 ? 0.8 : 1.0;
            const double w[3] = {0.5 * t, 0.5 * t * std::cos(2 * theta),
                                 0.5 * t * std::sin(2 * theta)};
            for (int k = 0; k < 3; ++k)
                c.analysis[static_cast<std::size_t>(k)][i] = static_cast<float>(w[k]);
            mosaic[i] = static_cast<float>(w[0] * s[0] + w[1] * s[1] + w[2] * s[2]);
        }
    test::TempDir tmp;
    {
        auto writer = SessionWriter::create(tmp / "s", manifest(sony.angles_deg()));
        writer.add_record(record(0, 2), frame(mosaic));
        writer.mark_complete();
    }
    const Image ideal = reduce_microgrid_session(tmp / "s");
    EXPECT_GT(std::abs(ideal.channel("S1")[5 * kWidth + 5]), 50.0)
        << "the planted 0.8 transmission must show without the calibration";
    MicrogridSessionOptions options;
    options.pixel_calibration = c;
    const Image calibrated = reduce_microgrid_session(tmp / "s", options);
    EXPECT_EQ(microgrid_session_record(calibrated).frames_averaged, 2);
    // The calibration states no Stokes units, so neither does the record (not "counts": the
    // analysis vectors map from whatever units their sources had).
    EXPECT_EQ(microgrid_session_record(calibrated).units, "");
    options.pixel_calibration->stokes_units = "W/(m^2 sr)";
    EXPECT_EQ(microgrid_session_record(reduce_microgrid_session(tmp / "s", options)).units,
              "W/(m^2 sr)");
    EXPECT_EQ(calibrated.width(), kWidth / 2);
    // A Stokes image reduced from one frame, not from a session, has no session record.
    EXPECT_THAT(
        [&] { microgrid_session_record(reduce_microgrid(mosaic, kWidth, kHeight, sony)); },
        testing::ThrowsMessage<Error>(testing::HasSubstr("no attribute 'records_averaged'")));
    for (std::size_t i = 0; i < calibrated.pixel_count(); ++i) {
        ASSERT_NEAR(calibrated.channel("S0")[i], s[0], 1e-2);
        ASSERT_NEAR(calibrated.channel("S1")[i], s[1], 1e-2);
        ASSERT_NEAR(calibrated.channel("S2")[i], s[2], 1e-2);
    }
    c.width = kWidth + 2;
    options.pixel_calibration = c;
    EXPECT_THAT([&] { reduce_microgrid_session(tmp / "s", options); },
                ::testing::ThrowsMessage<Error>(
                    HasSubstr("per-pixel calibration is 18×12, the session's camera 16×12")));
}

TEST(MicrogridSession, RefusesARotatingPolarizerSessionAndOneWithoutPolarizerRecords) {
    test::TempDir tmp;
    { auto writer = SessionWriter::create(tmp / "plain", manifest(std::nullopt)); }
    EXPECT_FALSE(is_microgrid_session(tmp / "plain"));
    EXPECT_THAT([&] { reduce_microgrid_session(tmp / "plain"); },
                ::testing::ThrowsMessage<Error>(
                    HasSubstr("session.json: camera.microgrid_pattern_deg is null")));
    {
        auto writer =
            SessionWriter::create(tmp / "empty", manifest(std::array<double, 4>{90, 45, 135, 0}));
    }
    EXPECT_THAT([&] { reduce_microgrid_session(tmp / "empty"); },
                ::testing::ThrowsMessage<Error>(HasSubstr("no polarizer record to reduce")));
    {
        // Four distinct angles that do not determine S1 and S2 are read, and refused here.
        auto writer =
            SessionWriter::create(tmp / "degenerate", manifest(std::array<double, 4>{0, 1, 2, 3}));
    }
    EXPECT_THAT([&] { reduce_microgrid_session(tmp / "degenerate"); },
                ::testing::ThrowsMessage<Error>(HasSubstr("camera.microgrid_pattern_deg")));
}

}  // namespace
}  // namespace tirpol::calibration
