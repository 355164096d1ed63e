// The calibration subcommands end to end through the real executable, on sessions written with
// core's SessionWriter: exit codes, messages that name the problem, and the physics of the outputs.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "test_support.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/core/session.h"

namespace {

using namespace tirpol;

using tirpol::test::CliRun;
using tirpol::test::run_cli;

constexpr int kW = 16, kH = 12;
constexpr double kGain = 100.0, kOffset = 5000.0;  // counts = offset + gain·L, noiseless

SessionManifest manifest(bool polarizer_in_beam) {
    SessionManifest m;
    m.created_utc = "2026-11-22T17:00:00Z";
    m.camera = {"sim://cli-test", "tirpol", "test", "1", "Mono16", kW, kH, 16, 30.0, {}};
    m.stage = {"sim://stage", "tirpol", "test", "1", "1", 1000.0};
    m.metadata = {{"polarizer_in_beam", polarizer_in_beam}};
    return m;
}

Image frame(double radiance) {
    Image im(kW, kH);
    im.add_channel("counts", static_cast<float>(kOffset + kGain * radiance));
    im.add_channel("counts_std", 2.0f);
    return im;
}

SessionRecord record(RecordKind kind, const std::string& stem, double angle,
                     std::optional<double> t) {
    SessionRecord r;
    r.kind = kind;
    r.file = session_frame_file(stem);
    r.angle_deg_requested = r.angle_deg_measured = angle;
    r.blackbody_temperature_k = t;
    r.frames = 16;
    r.first_timestamp_ns = 1795359560000000000;
    r.last_timestamp_ns = r.first_timestamp_ns + 1000;
    return r;
}

void write_lab(const std::filesystem::path& dir, const std::vector<double>& temps) {
    const Band band(8.0, 14.0);
    auto w = SessionWriter::create(dir, manifest(false));
    int i = 0;
    for (double t : temps)
        w.add_record(record(RecordKind::Blackbody, "bb" + std::to_string(i++), 0.0, t),
                     frame(band.radiance(t)));
    w.mark_complete();
}

TEST(CalibrationCli, RadiometricCalibrationTemperatureAndReduce) {
    test::TempDir dir;
    const Band band(8.0, 14.0);
    write_lab(dir / "lab", {283.15, 303.15, 323.15});
    const auto cal = (dir / "cal.exr").string();
    CliRun r = run_cli("calibrate radiometric " + (dir / "lab").string() + " -o " + cal);
    ASSERT_EQ(r.exit_code, 0) << r.out;

    // A blackbody frame at 300 K reads 300 K.
    const auto t_out = (dir / "t.exr").string();
    Image bb = frame(band.radiance(300.0));
    write_exr(dir / "bb300.exr", bb);
    r = run_cli("temperature " + (dir / "bb300.exr").string() + " --calibration " + cal + " -o " +
                t_out);
    ASSERT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NEAR(read_exr(t_out).at("temperature_k", 3, 4), 300.0, 1e-3);

    // A scene polarized along the image rows (S1 = 0.1·S0) through an ideal polarizer (Malus).
    const double s0 = band.radiance(295.0), s1 = 0.1 * s0;
    {
        auto w = SessionWriter::create(dir / "scene", manifest(true));
        for (double a : {0.0, 45.0, 90.0, 135.0}) {
            const double i = 0.5 * (s0 + s1 * std::cos(2.0 * a * 3.14159265358979 / 180.0));
            w.add_record(record(RecordKind::Polarizer, "p" + std::to_string(static_cast<int>(a)), a,
                                std::nullopt),
                         frame(i));
        }
        w.mark_complete();
    }
    const auto stokes = (dir / "stokes.exr").string();
    r = run_cli("reduce " + (dir / "scene").string() + " --calibration " + cal + " -o " + stokes);
    ASSERT_EQ(r.exit_code, 0) << r.out;
    const Image s = read_exr(stokes);
    EXPECT_NEAR(s.at("S0", 5, 5), s0, 1e-3);
    EXPECT_NEAR(s.at("S1", 5, 5), s1, 1e-3);
    EXPECT_NEAR(s.at("S2", 5, 5), 0.0, 1e-3);
    EXPECT_NEAR(s.at("DoLP", 5, 5), 0.1, 1e-4);
    for (const char* c : {"S0_std", "S1_std", "S2_std", "DoLP_std", "AoP_std"})
        EXPECT_TRUE(s.has_channel(c)) << c;
    EXPECT_EQ(std::get<std::string>(s.attributes().at("units_AoP")), "deg");

    // Emissivity from the Stokes EXR: reflector and target are the same uniform image here, so
    // L_BB must exceed L_dw — a warm target gives a clear error, not a silent number.
    test::write_text(dir / "rois.yaml",
                     "reflector: {rect: [0, 0, 4, 4]}\ntargets:\n"
                     "  - {name: t, rect: [8, 4, 4, 4], view_angle_deg: 30, temperature_k: 250}\n");
    r = run_cli("extract-emissivity " + stokes + " " + (dir / "rois.yaml").string() + " -o " +
                (dir / "e.csv").string());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.out.find("does not exceed the downwelled"), std::string::npos) << r.out;
}

TEST(CalibrationCli, ReduceWithDriftCorrectionInterpolatesBetweenShutterRecords) {
    // The offset drifts 40 → 80 counts linearly over 100 s; shutter records at 295 K at 0 and 100
    // s, an unpolarized 300 K scene at 20, 40, 60, 80 s: linear interpolation recovers it exactly.
    test::TempDir dir;
    const Band band(8.0, 14.0);
    write_lab(dir / "lab", {283.15, 303.15, 323.15});
    const auto cal = (dir / "cal.exr").string();
    ASSERT_EQ(run_cli("calibrate radiometric " + (dir / "lab").string() + " -o " + cal).exit_code,
              0);
    {
        auto w = SessionWriter::create(dir / "scene", manifest(true));
        auto add = [&](RecordKind kind, const std::string& stem, double angle,
                       std::optional<double> t, double time_s, double radiance) {
            SessionRecord r = record(kind, stem, angle, t);
            r.first_timestamp_ns = r.last_timestamp_ns =
                1795359560000000000 + static_cast<std::int64_t>(time_s * 1e9);
            Image f = frame(radiance);
            for (auto& c : f.channel("counts")) c += static_cast<float>(40.0 + 0.4 * time_s);
            w.add_record(r, f);
        };
        add(RecordKind::Shutter, "shutter0", 0.0, 295.0, 0.0, band.radiance(295.0));
        for (int k = 0; k < 4; ++k)
            add(RecordKind::Polarizer, fmt::format("p{}", 45 * k), 45.0 * k, std::nullopt,
                20.0 * (k + 1), 0.5 * band.radiance(300.0));
        add(RecordKind::Shutter, "shutter1", 0.0, 295.0, 100.0, band.radiance(295.0));
        w.mark_complete();
    }
    const auto out = (dir / "stokes.exr").string();
    const CliRun raw =
        run_cli("reduce " + (dir / "scene").string() + " --calibration " + cal + " -o " + out);
    ASSERT_EQ(raw.exit_code, 0) << raw.out;
    EXPECT_GT(std::abs(band.brightness_temperature(read_exr(out).at("S0", 5, 5)) - 300.0), 1.0);
    // The same output again: an existing file is replaced only with --force (docs/cli.md).
    const CliRun r = run_cli("reduce " + (dir / "scene").string() + " --calibration " + cal +
                             " --drift-correction --force -o " + out);
    ASSERT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NE(r.out.find("drift correction (shutter records (2), interpolated in time): offset "
                         "shift 48.00 … 72.00 counts"),
              std::string::npos)
        << r.out;
    const Image s = read_exr(out);
    EXPECT_NEAR(band.brightness_temperature(s.at("S0", 5, 5)), 300.0, 1e-3);
    const auto& shift = std::get<std::vector<double>>(s.attributes().at("drift_offset_counts"));
    ASSERT_EQ(shift.size(), 4u);
    EXPECT_NEAR(shift[1], 56.0, 1e-2);
    EXPECT_NEAR(std::get<std::vector<double>>(s.attributes().at("drift_time_s"))[3], 60.0, 1e-9);
}

TEST(CalibrationCli, FlirTemperatureOfARawExrWithSc660Constants) {
    // Thermimage's SC660 constants; raw 18109 under blackbody conditions is 296.7743 K
    // (flir_test.cpp).
    test::TempDir dir;
    Image raw(4, 3);
    raw.add_channel("counts", 18109.0f);
    write_exr(dir / "raw.exr", raw);
    const CliRun r =
        run_cli("flir-temperature " + (dir / "raw.exr").string() +
                " --planck 21106.77,0.012545258,1501,1,-7340 -o " + (dir / "t.exr").string());
    ASSERT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NEAR(read_exr(dir / "t.exr").at("temperature_k", 2, 1), 296.7743, 1e-3);
    const CliRun bad =
        run_cli("flir-temperature " + (dir / "raw.exr").string() +
                " --planck 21106.77,0.012545258,1501,1,-7340 --window-transmission 0 -o " +
                (dir / "u.exr").string());
    EXPECT_EQ(bad.exit_code,
              2);  // outside the limits table's [0.01, 1]: a usage error (docs/cli.md)
    EXPECT_NE(bad.out.find("--window-transmission: 0 is outside [0.01, 1]"), std::string::npos)
        << bad.out;
}

TEST(CalibrationCli, NoiseReportGivesNedtFromAFrameStack) {
    // 32 frames of a 300 K blackbody, temporal σ = 8 counts (uniform ±√3σ from a fixed LCG), gain
    // 100 counts per W/(m²·sr): NEDT = 8/(100·dL/dT(300 K)).
    test::TempDir dir;
    const Band band(8.0, 14.0);
    write_lab(dir / "lab", {283.15, 323.15});
    ASSERT_EQ(run_cli("calibrate radiometric " + (dir / "lab").string() + " -o " +
                      (dir / "c.exr").string())
                  .exit_code,
              0);
    std::uint64_t state = 12345;
    auto uniform = [&] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5;
    };
    std::filesystem::create_directories(dir / "stack");
    for (int t = 0; t < 32; ++t) {
        Image f(kW, kH);
        auto& c = f.add_channel("counts");
        for (auto& v : c)
            v = static_cast<float>(kOffset + kGain * band.radiance(300.0) +
                                   8.0 * std::sqrt(12.0) * uniform());
        write_exr(dir / "stack" / fmt::format("f{}.exr", 100 + t), f);
    }
    const CliRun r =
        run_cli("noise " + (dir / "stack").string() + " -o " + (dir / "n.json").string() +
                " --calibration " + (dir / "c.exr").string() + " --temperature-k 300");
    ASSERT_EQ(r.exit_code, 0) << r.out;
    const auto j = nlohmann::json::parse(read_file(dir / "n.json"));
    EXPECT_EQ(j["frames"].get<int>(), 32);
    const double expected = 8.0 / (kGain * band.radiance_dT(300.0));
    EXPECT_NEAR(j["nedt_median_k"].get<double>(), expected, 0.1 * expected);
    EXPECT_NEAR(j["three_d_noise_counts"]["sigma_tvh"].get<double>(), 8.0, 0.8);
    EXPECT_EQ(j["nedt_vs_frames_averaged"].size(), 4u);  // n = 1, 2, 4, 8
}

TEST(CalibrationCli, BadSessionsGiveExitOneAndNameTheProblem) {
    test::TempDir dir;
    write_lab(dir / "one", {300.0, 300.0});
    CliRun r = run_cli("calibrate radiometric " + (dir / "one").string() + " -o " +
                       (dir / "c.exr").string());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.out.find("1 distinct temperature"), std::string::npos) << r.out;
    EXPECT_FALSE(std::filesystem::exists(dir / "c.exr"));  // no partial output

    write_lab(dir / "lab", {283.15, 323.15});
    ASSERT_EQ(run_cli("calibrate radiometric " + (dir / "lab").string() + " -o " +
                      (dir / "c.exr").string())
                  .exit_code,
              0);
    {
        auto w = SessionWriter::create(dir / "two_angles", manifest(true));
        w.add_record(record(RecordKind::Polarizer, "p0", 0.0, std::nullopt), frame(20.0));
        w.add_record(record(RecordKind::Polarizer, "p90", 90.0, std::nullopt), frame(20.0));
    }
    r = run_cli("reduce " + (dir / "two_angles").string() + " --calibration " +
                (dir / "c.exr").string() + " -o " + (dir / "s.exr").string());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.out.find("at least 3 angles"), std::string::npos) << r.out;
    EXPECT_FALSE(std::filesystem::exists(dir / "s.exr"));

    write_file_atomic(dir / "two_angles" / "session.json",
                      "{\"schema\": \"tirpol.session\", \"records\": [");
    r = run_cli("reduce " + (dir / "two_angles").string() + " --calibration " +
                (dir / "c.exr").string() + " -o " + (dir / "s.exr").string());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.out.find("session.json"), std::string::npos) << r.out;

    r = run_cli("flir-temperature " + (dir / "c.exr").string() + " --planck 1,2,3 -o " +
                (dir / "f.exr").string());
    EXPECT_EQ(r.exit_code, 2);
}

}  // namespace
