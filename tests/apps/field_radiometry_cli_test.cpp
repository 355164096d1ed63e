// Field radiometry through the real executable: an FPA-dependent calibration from
// sessions at three camera temperatures, applied at another camera temperature by `temperature`,
// the extrapolation warning, the calibration summary, and `noise` on a raw file.

#include <fmt/format.h>
#include <gtest/gtest.h>

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
constexpr double kReferenceFpaK = 303.0;

/// A camera whose response follows its FPA temperature: counts = 5000 + 60·ΔT + 100·(1 −
/// 0.006·ΔT)·L.
float drifting_counts(double radiance, double fpa_k) {
    const double dt = fpa_k - kReferenceFpaK;
    return static_cast<float>(5000.0 + 60.0 * dt + 100.0 * (1.0 - 0.006 * dt) * radiance);
}

Image frame(double radiance, double fpa_k) {
    Image im(kW, kH);
    im.add_channel("counts", drifting_counts(radiance, fpa_k));
    im.add_channel("counts_std", 2.0f);
    return im;
}

void write_warm_up_session(const std::filesystem::path& dir, double fpa_k) {
    SessionManifest m;
    m.created_utc = "2026-11-23T20:00:00Z";
    m.camera = {"sim://drifting", "tirpol", "test", "1", "Mono16", kW, kH, 16, 30.0, {}};
    m.stage = {"sim://stage", "tirpol", "test", "1", "1", 1000.0};
    m.metadata = {{"polarizer_in_beam", false}};
    auto w = SessionWriter::create(dir, m);
    const Band band(8.0, 14.0);
    for (double t : {283.15, 303.15, 323.15}) {
        SessionRecord r;
        r.kind = RecordKind::Blackbody;
        r.file = session_frame_file(fmt::format("bb_{:.0f}", t));
        r.blackbody_temperature_k = t;
        r.frames = 16;
        r.first_timestamp_ns = 1795359560000000000;
        r.last_timestamp_ns = r.first_timestamp_ns + 1000;
        r.fpa_temperature_k = fpa_k;
        w.add_record(r, frame(band.radiance(t), fpa_k));
    }
    w.mark_complete();
}

TEST(FieldRadiometryCli,
     FpaCalibrationFromThreeSessionsReadsTrueTemperatureAtAnotherCameraTemperature) {
    test::TempDir dir;
    const Band band(8.0, 14.0);
    std::string sessions;
    for (double fpa : {296.0, 303.0, 310.0}) {
        write_warm_up_session(dir / fmt::format("fpa{:.0f}", fpa), fpa);
        sessions += " " + (dir / fmt::format("fpa{:.0f}", fpa)).string();
    }
    const auto cal = (dir / "cal.exr").string();
    CliRun r = run_cli("calibrate radiometric" + sessions + " --fpa-degree 1 -o " + cal);
    ASSERT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NE(r.out.find("FPA-temperature model of degree 1"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("residual per set-point"), std::string::npos) << r.out;
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "cal.summary" / "index.html"));

    // A 300 K scene at FPA 308 K (between calibrated states), the FPA temperature in the EXR
    // header.
    Image scene = frame(band.radiance(300.0), 308.0);
    scene.attributes()["fpa_temperature_k"] = 308.0;
    write_exr(dir / "scene.exr", scene);
    r = run_cli("temperature " + (dir / "scene.exr").string() + " --calibration " + cal + " -o " +
                (dir / "t.exr").string());
    ASSERT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NEAR(read_exr(dir / "t.exr").at("temperature_k", 5, 5), 300.0, 0.01);
    EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;

    // The single-state calibration of the 303 K session reads that frame kelvins off.
    ASSERT_EQ(run_cli("calibrate radiometric " + (dir / "fpa303").string() + " -o " +
                      (dir / "one.exr").string())
                  .exit_code,
              0);
    r = run_cli("temperature " + (dir / "scene.exr").string() + " --calibration " +
                (dir / "one.exr").string() + " -o " + (dir / "t1.exr").string());
    ASSERT_EQ(r.exit_code, 0) << r.out;
    EXPECT_GT(std::abs(read_exr(dir / "t1.exr").at("temperature_k", 5, 5) - 300.0), 1.0);

    // A 250 K scene is below the calibrated 283.15–323.15 K: computed, but with a warning.
    write_exr(dir / "cold.exr", frame(band.radiance(250.0), 303.0));
    r = run_cli("temperature " + (dir / "cold.exr").string() + " --calibration " + cal +
                " --fpa-temperature-k 303 -o " + (dir / "t2.exr").string());
    ASSERT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NE(r.out.find("outside the calibrated blackbody range 283.15–323.15 K"),
              std::string::npos)
        << r.out;

    // Without an FPA temperature, the FPA-dependent calibration refuses (exit 1) and says why.
    write_exr(dir / "nofpa.exr", frame(band.radiance(300.0), 303.0));
    r = run_cli("temperature " + (dir / "nofpa.exr").string() + " --calibration " + cal + " -o " +
                (dir / "t3.exr").string());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.out.find("FPA temperature"), std::string::npos) << r.out;
}

TEST(FieldRadiometryCli, NoiseReadsARawFileWithItsShape) {
    // PNG/TIFF folders are read by the same loader, tested in tests/calibration (which can write
    // them with OpenCV); here a headerless uint16 raw file of 4 frames goes through the CLI.
    test::TempDir dir;
    std::string bytes;
    for (int t = 0; t < 4; ++t)
        for (int i = 0; i < kW * kH; ++i) {
            const int v = 1000 + ((t * 7 + i * 3) % 5);
            bytes.push_back(static_cast<char>(v & 0xff));
            bytes.push_back(static_cast<char>(v >> 8));
        }
    write_file_atomic(dir / "stack.raw", bytes);
    const CliRun r =
        run_cli("noise " + (dir / "stack.raw").string() +
                fmt::format(" --raw-shape {} {}", kW, kH) + " -o " + (dir / "n.json").string());
    ASSERT_EQ(r.exit_code, 0) << r.out;
    const auto j = nlohmann::json::parse(read_file(dir / "n.json"));
    EXPECT_EQ(j["frames"].get<int>(), 4);
    EXPECT_EQ(j["convention"].get<std::string>(), "sample (N-1, as pyradi ry3dnoise)");
    std::filesystem::create_directories(dir / "empty");
    const CliRun e =
        run_cli("noise " + (dir / "empty").string() + " -o " + (dir / "e.json").string());
    EXPECT_EQ(e.exit_code, 1);
    EXPECT_NE(e.out.find("no frame files"), std::string::npos) << e.out;
}

}  // namespace
