// `tirpol emissivity` and `tirpol brdf`: JSON output consistent with the library, CSV/plot files,
// and exit codes (1 for bad input, 2 for bad usage).

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "test_support.h"

namespace {

using tirpol::test::CliRun;
using tirpol::test::run_cli;

std::string material(const char* name) {
    return (tirpol::test::source_dir() / "config/materials" / name).string();
}

// Water at 10 µm (Hale & Querry 1973: n = 1.218, k = 0.0508): normal emissivity 1 − R = 0.9898
// (R = ((n−1)² + k²)/((n+1)² + k²)), and emission polarized in the plane of emission at 60°.
TEST(MaterialsCli, EmissivityJsonForWater) {
    const CliRun r = run_cli(
        "emissivity " + material("water.yaml") + " --wavelength-um 10 --angles-deg 0,60 --json",
        false);
    ASSERT_EQ(r.exit_code, 0) << r.out;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j["rows"].size(), 2u);
    const double n = 1.218, k = 0.0508;
    const double R = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
    EXPECT_NEAR(j["rows"][0]["e_s0"].get<double>(), 1.0 - R, 1e-9);
    EXPECT_NEAR(j["rows"][0]["dhr"].get<double>(), R, 1e-9);
    EXPECT_LT(j["rows"][1]["e_s1"].get<double>(), 0.0);
}

TEST(MaterialsCli, EmissivityBandWritesCsvAndPlot) {
    tirpol::test::TempDir dir;
    const auto csv = dir / "e.csv", png = dir / "e.png";
    const CliRun r = run_cli("emissivity " + material("flat_black_paint.yaml") +
                             " --band-um 8 14 --angles-deg 0:80:20 --csv " + csv.string() +
                             " --plot " + png.string());
    ASSERT_EQ(r.exit_code, 0) << r.out;
    std::ifstream in(csv);
    std::string header;
    std::getline(in, header);
    EXPECT_EQ(header, "angle_deg,e_s0,e_s1,e_s2,e_s3,dolp,dhr");
    int rows = 0;
    for (std::string line; std::getline(in, line);) ++rows;
    EXPECT_EQ(rows, 5);
    EXPECT_GT(std::filesystem::file_size(png), 1000u);
}

TEST(MaterialsCli, BrdfJsonIsReciprocalMuellerMatrix) {
    const std::string base =
        "brdf " + material("flat_black_paint.yaml") + " --wavelength-um 10 --json ";
    const CliRun a = run_cli(base + "--incident-deg 30 10 --exitant-deg 50 200", false);
    const CliRun b = run_cli(base + "--incident-deg 50 200 --exitant-deg 30 10", false);
    ASSERT_EQ(a.exit_code, 0) << a.out;
    ASSERT_EQ(b.exit_code, 0) << b.out;
    const auto ma = nlohmann::json::parse(a.out)["mueller_brdf_per_sr"],
               mb = nlohmann::json::parse(b.out)["mueller_brdf_per_sr"];
    // M(wo→wi) = Q M(wi→wo)ᵀ Q, Q = diag(1, 1, −1, 1) (pbrdf.h).
    const double q[4] = {1, 1, -1, 1};
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            EXPECT_NEAR(mb[r][c].get<double>(), q[r] * q[c] * ma[c][r].get<double>(), 1e-12);
}

TEST(MaterialsCli, BadInputsGiveClearErrors) {
    CliRun r =
        run_cli("emissivity " + material("water.yaml") + " --wavelength-um 30 --angles-deg 0");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.out.find("outside"), std::string::npos) << r.out;
    r = run_cli("emissivity " + material("water.yaml") +
                " --wavelength-um 10 --angles-deg 0:100:10");
    EXPECT_EQ(r.exit_code, 2);  // an option value outside its range: usage
    EXPECT_NE(r.out.find("outside [0, 90]"), std::string::npos) << r.out;
    EXPECT_EQ(run_cli("emissivity " + material("water.yaml") + " --angles-deg 0").exit_code, 2);
    EXPECT_EQ(run_cli("brdf " + material("water.yaml") + " --wavelength-um 10 --incident-deg 30")
                  .exit_code,
              2);
}

}  // namespace
