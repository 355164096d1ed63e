// End to end on synthetic sessions written with core's SessionWriter: laboratory radiometric
// calibration, field polarimetric calibration (wire-grid τ/B + analyzer from a known source),
// reduction to Stokes and emissivity extraction recover the planted truth.

#include "tirpol/calibration/session_calibration.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>

#include "test_support.h"
#include "tirpol/calibration/emissivity_extraction.h"
#include "tirpol/calibration/synthetic_session.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/interrupt_signals.h"

namespace tirpol::calibration {
namespace {

/// The manifest of a session taken with the synthetic camera and stage.
SessionManifest synthetic_manifest(const SyntheticCamera& cam) {
    SessionManifest m;
    m.created_utc = "2026-11-22T17:00:00Z";
    m.camera = {"sim://synthetic",
                "tirpol",
                "synthetic-uncooled",
                "0001",
                "Mono14",
                cam.width,
                cam.height,
                14,
                30.0,
                {}};
    m.stage = {"sim://stage", "tirpol", "synthetic-stage", "0001", "1.0", 1000.0};
    return m;
}

class SessionCalibration : public testing::Test {
protected:
    static void SetUpTestSuite() {
        dir_ = new test::TempDir("tirpol-calib-session");
        write_synthetic_sessions(dir_->path(), SyntheticCamera{},
                                 synthetic_panel_scene(64, 48, Band(8.0, 14.0)), Band(8.0, 14.0));
    }
    static void TearDownTestSuite() { delete dir_; }
    static std::filesystem::path root() { return dir_->path(); }
    static test::TempDir* dir_;
};
test::TempDir* SessionCalibration::dir_ = nullptr;

TEST_F(SessionCalibration, RadiometricFindsPlantedBadPixelsAndSaturationLevel) {
    const SyntheticCamera cam;
    const auto cal = calibrate_radiometric_session(root() / "lab", Band(8.0, 14.0));
    auto bits = [&](int x, int y) {
        return static_cast<std::uint32_t>(cal.bad[static_cast<std::size_t>(y * cam.width + x)]);
    };
    EXPECT_TRUE(bits(cam.dead_x, cam.dead_y) & kDead);
    EXPECT_TRUE(bits(cam.hot_x, cam.hot_y) & kHot);
    EXPECT_TRUE(bits(cam.noisy_x, cam.noisy_y) & kNoisy);
    EXPECT_EQ(cal.bad_count(), 3u);
    EXPECT_EQ(cal.bad_count(kNonLinear), 0u);
    EXPECT_THAT(cal.camera_id, testing::HasSubstr("sim://synthetic"));
    // The lab session says the polarizer was out of the beam; the field one says it was in.
    EXPECT_THROW(calibrate_radiometric_session(root() / "polcal", Band(8.0, 14.0)), Error);
    EXPECT_THROW(calibrate_polarimetric_session(root() / "lab", cal), Error);
}

TEST_F(SessionCalibration, PolarimetricCalibrationAndReductionRecoverTheSceneStokes) {
    const SyntheticCamera cam;
    const Band band(8.0, 14.0);
    const auto cal = calibrate_radiometric_session(root() / "lab", band);
    const auto pol = calibrate_polarimetric_session(root() / "polcal", cal);
    EXPECT_EQ(pol.analyzer_method, "known-source least squares");
    for (const auto& p : pol.analyzer.positions) {
        // Noise of the known-source means over ~3000 pixels is tiny; 0.2° and 20 % on a 100:1
        // extinction ratio (d = 0.980 ± 0.004) are the tolerances.
        EXPECT_NEAR(p.axis_angle_deg - p.nominal_angle_deg, cam.angle_offset_deg, 0.2);
        EXPECT_NEAR(p.extinction_ratio(), cam.extinction_ratio, 20.0);
    }
    test::TempDir out;
    write_polarimetric_calibration((out / "pol.yaml").string(), pol);
    const auto pol_back = read_polarimetric_calibration((out / "pol.yaml").string());
    EXPECT_EQ(pol_back.wire_grid.at(45.0).tau, pol.wire_grid.at(45.0).tau);
    EXPECT_NEAR(pol_back.analyzer.positions[2].axis_angle_deg,
                pol.analyzer.positions[2].axis_angle_deg, 1e-6);

    const Image truth = synthetic_panel_scene(cam.width, cam.height, band);
    const Image s = reduce_session(root() / "scene", cal, &pol_back);
    // Per-pixel noise: σ(counts mean) = 6/√16 = 1.5 counts → 0.015 W/(m²·sr) per angle, ÷ τ ≈ 0.8
    // and through W⁺ (×√2 for S1): S1_std ≈ 0.03. Check the mean over the panel to 4 σ/√n and
    // each pixel to 5 of its own σ.
    double mean_err = 0.0;
    int n = 0;
    for (int y = 12; y < 36; ++y)
        for (int x = 26; x < 38; ++x) {
            const std::size_t i = s.index(x, y);
            ASSERT_NEAR(s.channel("S1")[i], truth.channel("S1")[i],
                        5.0 * s.channel("S1_std")[i] + 1e-3)
                << x << "," << y;
            mean_err += s.channel("S1")[i] - truth.channel("S1")[i];
            ++n;
        }
    EXPECT_LT(std::abs(mean_err / n), 4.0 * 0.04 / std::sqrt(static_cast<double>(n)));
    EXPECT_NEAR(s.channel("S0")[s.index(30, 20)], truth.channel("S0")[s.index(30, 20)], 0.15);
    EXPECT_EQ(std::get<int>(s.attributes().at("saturated_pixels")), 0);

    // Emissivity extraction from the reduced image: reflector x 4..15, panel x 24..39.
    EmissivityRois rois;
    rois.reflector.rect = {5, 10, 9, 28};
    rois.targets = {{"panel", {26, 12, 12, 24}, 45.0, 300.0, 0.05, std::nullopt}};
    const auto e = extract_emissivity(s, rois, band);
    EXPECT_NEAR(e[0].eps_s0, 0.93, std::max(2.0 * e[0].eps_s0_std, 0.005));
    EXPECT_NEAR(e[0].eps_s1, -0.035, std::max(2.0 * e[0].eps_s1_std, 0.002));
    EXPECT_NEAR(e[0].eps_s2, 0.01, std::max(2.0 * e[0].eps_s2_std, 0.002));
}

TEST_F(SessionCalibration, WithoutWireGridRemovalTheSkyReflectionBiasesS1) {
    const auto cal = calibrate_radiometric_session(root() / "lab", Band(8.0, 14.0));
    SessionReductionOptions opt;
    opt.update_offset = true;
    const Image naive = reduce_session(root() / "scene", cal, nullptr, opt);
    const Image truth = synthetic_panel_scene(64, 48, Band(8.0, 14.0));
    // The grid reflects a partly polarized sky (±30 % with angle): S1 is off by far more than
    // noise.
    EXPECT_GT(std::abs(naive.channel("S1")[naive.index(30, 20)] -
                       truth.channel("S1")[naive.index(30, 20)]),
              0.3);
    const auto pol = calibrate_polarimetric_session(root() / "polcal", cal);
    EXPECT_THROW(reduce_session(root() / "scene", cal, &pol, opt),
                 Error);  // drift would be removed twice
}

TEST_F(SessionCalibration, ASetCancelFlagStopsTheSessionReduction) {
    const auto cal = calibrate_radiometric_session(root() / "lab", Band(8.0, 14.0));
    const std::atomic<bool> cancel{true};
    SessionReductionOptions opt;
    opt.cancel = &cancel;
    EXPECT_THROW(reduce_session(root() / "scene", cal, nullptr, opt), Cancelled);
}

TEST_F(SessionCalibration, SaturatedScenePixelsAreNaNAndTooManyAreAnError) {
    const SyntheticCamera cam;
    const Band band(8.0, 14.0);
    const auto cal = calibrate_radiometric_session(root() / "lab", band);
    const Image scene = synthetic_panel_scene(cam.width, cam.height, band);
    auto write = [&](const std::filesystem::path& dir, int saturated) {
        SessionManifest m = synthetic_manifest(cam);
        auto w = SessionWriter::create(dir, m);
        for (double a : cam.angles_deg) {
            Image f = synthetic_record_frame(cam, scene, band, a, true, true,
                                             50u + static_cast<unsigned>(a));
            if (a == 45.0)
                for (int i = 0; i < saturated; ++i)
                    f.channel("counts")[static_cast<std::size_t>(7 * i)] = 16383.0f;
            SessionRecord r;
            r.file = session_frame_file(fmt::format("p{:g}", a));
            r.angle_deg_requested = r.angle_deg_measured = a;
            r.frames = 16;
            w.add_record(r, f);
        }
    };
    test::TempDir tmp;
    write(tmp / "few", 5);
    const Image s = reduce_session(tmp / "few", cal, nullptr);
    EXPECT_EQ(std::get<int>(s.attributes().at("saturated_pixels")), 5);
    EXPECT_TRUE(std::isnan(s.channel("S1")[7]));
    EXPECT_TRUE(std::isnan(s.channel("S0_std")[7]));
    EXPECT_FALSE(std::isnan(s.channel("S1")[8]));
    write(tmp / "many", 200);  // 6.5 % of the 64×48 pixels
    try {
        reduce_session(tmp / "many", cal, nullptr);
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::HasSubstr("saturated"));
        EXPECT_THAT(e.what(), testing::HasSubstr("p45.exr"));
    }
}

TEST_F(SessionCalibration, ReductionUsesTheMeasuredAngleAndRefusesOneOutsideTheTolerance) {
    // A mount that sits 2° past every requested angle (read back as such), an ideal analyzer, no
    // grid effects: frames exposed at θ + 2°. Reduced at the measured angle (schema v2) the scene's
    // S1/S2 come back; at the requested one (how a v1 session is read) they come back rotated by 2
    // × 2°.
    SyntheticCamera cam;
    cam.angle_offset_deg = 0.0;
    cam.extinction_ratio = 1e6;
    cam.t_max = 1.0;
    cam.grid_reflectance = cam.grid_emissivity = cam.ghost_radiance = 0.0;
    const Band band(8.0, 14.0);
    const auto cal = calibrate_radiometric_session(root() / "lab", band);
    const Image scene = synthetic_panel_scene(cam.width, cam.height, band);
    auto write = [&](const std::filesystem::path& dir, double tolerance_deg) {
        SessionManifest m = synthetic_manifest(cam);
        m.plan = {{"angle_tolerance_deg", tolerance_deg}};
        auto w = SessionWriter::create(dir, m);
        for (double a : cam.angles_deg) {
            SessionRecord r;
            r.file = session_frame_file(fmt::format("p{:g}", a));
            r.angle_deg_requested = a;
            r.angle_deg_measured = a + 2.0;
            r.frames = 16;
            w.add_record(r, synthetic_record_frame(cam, scene, band, a + 2.0, true, false,
                                                   70u + static_cast<unsigned>(a)));
        }
    };
    test::TempDir tmp;
    write(tmp / "v2", 3.0);
    // Angle of polarization of the panel's mean S1, S2, against the truth's, in degrees.
    auto aop_error_deg = [&](const Image& s) {
        double s1 = 0, s2 = 0, t1 = 0, t2 = 0;
        for (int y = 12; y < 36; ++y)
            for (int x = 26; x < 38; ++x) {
                s1 += s.channel("S1")[s.index(x, y)];
                s2 += s.channel("S2")[s.index(x, y)];
                t1 += scene.channel("S1")[s.index(x, y)];
                t2 += scene.channel("S2")[s.index(x, y)];
            }
        return std::abs(std::remainder(
            0.5 * (std::atan2(s2, s1) - std::atan2(t2, t1)) * 180.0 / std::numbers::pi, 180.0));
    };
    const double measured_error = aop_error_deg(reduce_session(tmp / "v2", cal, nullptr));
    std::filesystem::copy(tmp / "v2", tmp / "v1", std::filesystem::copy_options::recursive);
    auto j = nlohmann::json::parse(read_file(tmp / "v1" / "session.json"));
    j["schema_version"] = 1;
    write_file_atomic(tmp / "v1" / "session.json", j.dump());
    const double requested_error = aop_error_deg(reduce_session(tmp / "v1", cal, nullptr));
    // Reduced at the wrong angle the AoP is off by the 2° offset; at the measured one only by noise
    // (panel mean over 288 pixels: well under 0.5°).
    EXPECT_LT(measured_error, 0.5);
    EXPECT_NEAR(requested_error, 2.0, 0.5);

    write(tmp / "tight", 1.0);  // the 2° read-back is outside this plan's tolerance
    try {
        reduce_session(tmp / "tight", cal, nullptr);
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::HasSubstr("p0.exr"));
        EXPECT_THAT(e.what(), testing::HasSubstr("angle_tolerance_deg"));
    }
}

TEST_F(SessionCalibration, CorruptManifestAndMissingAngleGiveClearErrors) {
    const auto cal = calibrate_radiometric_session(root() / "lab", Band(8.0, 14.0));
    const auto pol = calibrate_polarimetric_session(root() / "polcal", cal);
    test::TempDir tmp;
    std::filesystem::copy(root() / "scene", tmp / "scene",
                          std::filesystem::copy_options::recursive);
    // Drop the 135° record from the manifest: the analyzer model needs it.
    auto manifest = nlohmann::json::parse(read_file(tmp / "scene" / "session.json"));
    auto& records = manifest["records"];
    records.erase(
        std::remove_if(
            records.begin(), records.end(),
            [](const auto& r) { return r["angle_deg_requested"].template get<double>() == 135.0; }),
        records.end());
    write_file_atomic(tmp / "scene" / "session.json", manifest.dump());
    try {
        reduce_session(tmp / "scene", cal, &pol);
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::HasSubstr("135°"));
    }
    // A truncated manifest.
    const std::string text = read_file(tmp / "scene" / "session.json");
    write_file_atomic(tmp / "scene" / "session.json", text.substr(0, text.size() / 2));
    try {
        reduce_session(tmp / "scene", cal, &pol);
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::HasSubstr("session.json"));
    }
}

}  // namespace
}  // namespace tirpol::calibration
