// Offset drift during a session (offset_drift.h): a synthetic uncooled camera whose offset drifts
// by 60 → 170 counts over the session (exponential warm-up), calibrated in the laboratory before
// the drift. The reduced brightness temperatures of two unpolarized areas come back within 50 mK
// with the drift correction (in-scene reference region, or interleaved shutter records) and err by
// > 1 K without.

#include "offset_drift.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include "test_support.h"
#include "tirpol/calibration/session_calibration.h"
#include "tirpol/core/error.h"

namespace tirpol::calibration {
namespace {

constexpr int kWidth = 32, kHeight = 24, kFrames = 16;
constexpr double kNoiseCounts = 6.0;      // temporal σ of one frame
constexpr double kRecordSpacingS = 20.0;  // between records
constexpr double kReferenceK = 303.15;    // in-scene reference blackbody (contact sensor)
const Band kBand(8.0, 14.0);

/// The drift of the camera's offset at time t since the session start (counts): 60 between the
/// laboratory and the field, then an exponential warm-up (τ = 400 s) towards 140 more.
double drift_counts(double t_s) { return 60.0 + 140.0 * (1.0 - std::exp(-t_s / 400.0)); }

struct Camera {
    std::vector<double> gain, offset;
    std::mt19937 rng{7};
    Camera() {
        std::normal_distribution<double> g(100.0, 5.0), o(5000.0, 150.0);
        for (int i = 0; i < kWidth * kHeight; ++i) {
            gain.push_back(g(rng));
            offset.push_back(o(rng));
        }
    }
    /// A record's mean counts for `radiance` (per pixel) with an offset drift of `drift`.
    Image frame(const std::vector<double>& radiance, double drift) {
        std::normal_distribution<double> noise(
            0.0, kNoiseCounts / std::sqrt(static_cast<double>(kFrames)));
        Image f(kWidth, kHeight);
        auto& counts = f.add_channel("counts");
        f.add_channel("counts_std", static_cast<float>(kNoiseCounts));
        for (std::size_t i = 0; i < counts.size(); ++i)
            counts[i] = static_cast<float>(offset[i] + drift + gain[i] * radiance[i] + noise(rng));
        return f;
    }
};

SessionManifest manifest(nlohmann::json plan) {
    SessionManifest m;
    m.created_utc = "2026-11-23T23:00:00Z";
    m.camera = {"sim://synthetic",
                "tirpol",
                "drifting-uncooled",
                "0001",
                "Mono16",
                kWidth,
                kHeight,
                16,
                30.0,
                {}};
    m.stage = {"sim://stage", "tirpol", "synthetic-stage", "0001", "1.0", 1000.0};
    m.plan = std::move(plan);
    return m;
}

SessionRecord record(RecordKind kind, const std::string& file, double t_s) {
    SessionRecord r;
    r.kind = kind;
    r.file = session_frame_file(file);
    r.frames = kFrames;
    r.first_timestamp_ns = 1'800'000'000'000'000'000 + static_cast<std::int64_t>(t_s * 1e9);
    r.last_timestamp_ns = r.first_timestamp_ns;
    return r;
}

/// Laboratory session: blackbody at 283/303/323 K, no polarizer, before any drift.
RadiometricCalibration laboratory_calibration(Camera& cam, const std::filesystem::path& dir) {
    auto w = SessionWriter::create(dir, manifest(nlohmann::json::object()));
    for (double t : {283.15, 303.15, 323.15}) {
        SessionRecord r = record(RecordKind::Blackbody, fmt::format("bb_{:.0f}", t), 0.0);
        r.blackbody_temperature_k = t;
        w.add_record(r, cam.frame(std::vector<double>(kWidth * kHeight, kBand.radiance(t)), 0.0));
    }
    return calibrate_radiometric_session(dir, kBand);
}

/// The scene: left half 290 K, right half 312 K, the reference blackbody (6×6 at x, y = 2) at
/// kReferenceK; all unpolarized, so each record through the ideal polarizer sees half the radiance.
std::vector<double> scene_s0() {
    std::vector<double> s0(kWidth * kHeight);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
            s0[y * kWidth + x] = kBand.radiance(x < 2 + 6 && y < 2 + 6 ? kReferenceK
                                                : x < kWidth / 2       ? 290.0
                                                                       : 312.0);
    return s0;
}

/// A scene session of 6 repeats × 4 angles; `shutter_every` > 0 puts a shutter record at 295 K
/// before every that many scene records and one at the end. Returns the true drift per scene
/// record.
std::vector<double> write_scene(Camera& cam, const std::filesystem::path& dir,
                                const nlohmann::json& plan, int shutter_every) {
    auto w = SessionWriter::create(dir, manifest(plan));
    const std::vector<double> s0 = scene_s0();
    std::vector<double> half(s0.size());
    for (std::size_t i = 0; i < s0.size(); ++i) half[i] = 0.5 * s0[i];
    const int n_scene = 24;
    double t = 0.0;
    int shutters = 0;
    auto shutter = [&] {
        SessionRecord r = record(RecordKind::Shutter, fmt::format("shutter_{}", shutters++), t);
        r.blackbody_temperature_k = 295.0;
        w.add_record(
            r, cam.frame(std::vector<double>(s0.size(), kBand.radiance(295.0)), drift_counts(t)));
        t += kRecordSpacingS;
    };
    std::vector<double> truth;
    for (int k = 0; k < n_scene; ++k) {
        if (shutter_every > 0 && k % shutter_every == 0) shutter();
        const double angle = 45.0 * (k % 4);
        SessionRecord r = record(RecordKind::Polarizer, fmt::format("pol_{:03}", k), t);
        r.angle_deg_requested = r.angle_deg_measured = angle;
        r.repeat = k / 4;
        truth.push_back(drift_counts(t));
        w.add_record(r, cam.frame(half, truth.back()));
        t += kRecordSpacingS;
    }
    if (shutter_every > 0) shutter();
    return truth;
}

/// Brightness temperature of the mean S0 over x in [x0, x1), y in [10, 20).
double area_temperature_k(const Image& s, int x0, int x1) {
    double sum = 0.0;
    int n = 0;
    for (int y = 10; y < 20; ++y)
        for (int x = x0; x < x1; ++x, ++n) sum += s.channel("S0")[s.index(x, y)];
    return kBand.brightness_temperature(sum / n);
}

void expect_drift_removed(const std::filesystem::path& scene, const RadiometricCalibration& cal,
                          const std::vector<double>& truth, double shift_tolerance_counts) {
    SessionReductionOptions opt;
    const Image raw = reduce_session(scene, cal, nullptr, opt);
    opt.drift_correction = true;
    const Image corrected = reduce_session(scene, cal, nullptr, opt);
    for (const auto& [x0, x1, t] : {std::tuple{2, 14, 290.0}, std::tuple{18, 30, 312.0}}) {
        EXPECT_NEAR(area_temperature_k(corrected, x0, x1), t, 0.05) << "x " << x0 << "–" << x1;
        EXPECT_GT(std::abs(area_temperature_k(raw, x0, x1) - t), 1.0) << "x " << x0 << "–" << x1;
    }
    const auto& shift =
        std::get<std::vector<double>>(corrected.attributes().at("drift_offset_counts"));
    const auto& sigma =
        std::get<std::vector<double>>(corrected.attributes().at("drift_offset_sigma_counts"));
    ASSERT_EQ(shift.size(), truth.size());
    for (std::size_t k = 0; k < truth.size(); ++k) {
        EXPECT_NEAR(shift[k], truth[k], shift_tolerance_counts) << "record " << k;
        EXPECT_GT(sigma[k], 0.0);
    }
}

TEST(OffsetDrift, InterpolatesLinearlyBetweenReferencesAndHoldsOutside) {
    const std::vector<OffsetDriftPoint> points{{10.0, 100.0, 0.3}, {20.0, 140.0, 0.4}};
    EXPECT_DOUBLE_EQ(interpolate_offset_drift(points, 15.0).shift_counts, 120.0);
    EXPECT_DOUBLE_EQ(interpolate_offset_drift(points, 12.5).shift_counts, 110.0);
    EXPECT_NEAR(interpolate_offset_drift(points, 15.0).sigma_counts, std::hypot(0.15, 0.2), 1e-12);
    EXPECT_DOUBLE_EQ(interpolate_offset_drift(points, 0.0).shift_counts, 100.0);
    EXPECT_DOUBLE_EQ(interpolate_offset_drift(points, 99.0).sigma_counts, 0.4);
    EXPECT_THROW(interpolate_offset_drift({}, 1.0), Error);
}

TEST(OffsetDrift, InSceneReferenceRegionRemovesTheDrift) {
    test::TempDir tmp("tirpol-offset-drift");
    Camera cam;
    const auto cal = laboratory_calibration(cam, tmp / "lab");
    const nlohmann::json plan = {{"scene_reference",
                                  {{"roi", {{"x", 2}, {"y", 2}, {"width", 6}, {"height", 6}}},
                                   {"temperature_k", kReferenceK},
                                   {"temperature_sigma_k", 0.02}}}};
    const auto truth = write_scene(cam, tmp / "scene", plan, 0);
    // Reference region: 36 pixels of 1.5 counts each, plus the calibration's offset error averaged
    // over them.
    expect_drift_removed(tmp / "scene", cal, truth, 2.0);
    const Image s = reduce_session(tmp / "scene", cal, nullptr, {.drift_correction = true});
    EXPECT_THAT(std::get<std::string>(s.attributes().at("drift_correction_source")),
                testing::HasSubstr("scene_reference"));
    // σ = the sensor's 20 mK through the polarizer (½·g·dL/dT·0.02 K) ⊕ the mean of 36 pixels
    // of 1.5 counts.
    const double expected =
        std::hypot(0.5 * 100.0 * kBand.radiance_dT(kReferenceK) * 0.02, 1.5 / 6.0);
    EXPECT_NEAR(std::get<std::vector<double>>(s.attributes().at("drift_offset_sigma_counts"))[0],
                expected, 0.05 * expected);
}

TEST(OffsetDrift, InterleavedShutterRecordsRemoveTheDrift) {
    test::TempDir tmp("tirpol-offset-drift");
    Camera cam;
    const auto cal = laboratory_calibration(cam, tmp / "lab");
    const auto truth = write_scene(cam, tmp / "scene", nlohmann::json::object(), 4);
    // Linear interpolation of the √t warm-up between shutters 100 s apart: < 3 counts except at the
    // start.
    expect_drift_removed(tmp / "scene", cal, truth, 6.0);
}

TEST(OffsetDrift, ASessionWithoutReferencesOrWithABadRoiIsRefused) {
    test::TempDir tmp("tirpol-offset-drift");
    Camera cam;
    const auto cal = laboratory_calibration(cam, tmp / "lab");
    write_scene(cam, tmp / "none", nlohmann::json::object(), 0);
    try {
        reduce_session(tmp / "none", cal, nullptr, {.drift_correction = true});
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::HasSubstr("scene_reference"));
    }
    write_scene(
        cam, tmp / "bad",
        {{"scene_reference",
          {{"roi", {{"x", 30}, {"y", 2}, {"width", 6}, {"height", 6}}}, {"temperature_k", 300.0}}}},
        0);
    try {
        reduce_session(tmp / "bad", cal, nullptr, {.drift_correction = true});
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::HasSubstr("plan.scene_reference.roi.width"));
    }
}

}  // namespace
}  // namespace tirpol::calibration
