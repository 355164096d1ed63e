// The `tirpol` executable: subcommand listing, exit codes and the JSON of `planck` and `info`.

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "test_support.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/radiometry.h"

namespace {

using tirpol::test::CliRun;
using tirpol::test::run_cli;

TEST(Cli, HelpListsSubcommands) {
    const CliRun r = run_cli("--help");
    EXPECT_EQ(r.exit_code, 0);
    for (const char* sub : {"info", "planck", "demo"})
        EXPECT_NE(r.out.find(sub), std::string::npos) << sub;
    EXPECT_EQ(run_cli("planck --help").exit_code, 0);
}

TEST(Cli, BadArgumentsExitWithTwo) {
    EXPECT_EQ(run_cli("").exit_code, 2);
    EXPECT_EQ(run_cli("no-such-command").exit_code, 2);
    const CliRun r = run_cli("planck --band-um 8 14");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.out.find("--temperature-k or --radiance"), std::string::npos) << r.out;
    EXPECT_EQ(run_cli("planck --temperature-k hot --band-um 8 14").exit_code, 2);
}

TEST(Cli, PlanckJsonMatchesTheLibraryAndInverts) {
    const CliRun r = run_cli("planck --temperature-k 300 --band-um 8 14 --json");
    ASSERT_EQ(r.exit_code, 0) << r.out;
    const auto j = nlohmann::json::parse(r.out);
    const tirpol::Band band(8.0, 14.0);
    EXPECT_DOUBLE_EQ(j["radiance_w_m2_sr"].get<double>(), band.radiance(300.0));
    EXPECT_DOUBLE_EQ(j["radiance_dT_w_m2_sr_k"].get<double>(), band.radiance_dT(300.0));
    const CliRun inv = run_cli("planck --radiance " + std::to_string(band.radiance(300.0)) +
                               " --band-um 8 14 --json");
    ASSERT_EQ(inv.exit_code, 0) << inv.out;
    EXPECT_NEAR(nlohmann::json::parse(inv.out)["brightness_temperature_k"].get<double>(), 300.0,
                1e-3);
}

TEST(Cli, PlanckRejectsNonPhysicalInputAsAUsageError) {
    const CliRun r = run_cli("planck --temperature-k -3 --band-um 8 14");
    EXPECT_EQ(r.exit_code, 2);  // values outside an option's range are usage errors (docs/cli.md)
    EXPECT_NE(
        r.out.find("--temperature-k: -3 is outside [1, 10000], a physical temperature in kelvin"),
        std::string::npos)
        << r.out;
    EXPECT_EQ(run_cli("planck --temperature-k 300 --band-um 14 8").exit_code, 2);
}

TEST(Cli, InfoDescribesAnExrAndNamesAMissingFile) {
    tirpol::test::TempDir dir;
    tirpol::Image img(4, 3);
    img.add_channel("S0", 2.0f);
    img.add_channel("S1", 0.0f)[5] = std::nanf("");
    img.attributes()["units"] = std::string("W/(m^2 sr)");
    tirpol::write_exr(dir / "s.exr", img);
    const CliRun r = run_cli("info --json " + (dir / "s.exr").string());
    ASSERT_EQ(r.exit_code, 0) << r.out;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["width"], 4);
    EXPECT_EQ(j["channels"]["S1"]["nan_count"], 1);
    EXPECT_DOUBLE_EQ(j["channels"]["S0"]["mean"].get<double>(), 2.0);
    EXPECT_EQ(j["attributes"]["units"], "W/(m^2 sr)");
    const CliRun missing = run_cli("info " + (dir / "missing.exr").string());
    EXPECT_EQ(missing.exit_code, 1);
    EXPECT_NE(missing.out.find("missing.exr: no such file"), std::string::npos) << missing.out;
}

}  // namespace

// --max-bounces follows the scene file's rule for sampling.max_bounces (scene.h
// max_bounces_problem): 0–100000, a safety cap; anything else is a clear error before rendering,
// exit code 1.
TEST(Cli, RenderMaxBouncesIsValidatedLikeTheSceneFile) {
    const tirpol::test::TempDir dir;
    const auto scene = tirpol::test::source_dir() / "config" / "scenes" / "panels_night.yaml";
    for (const char* bad : {"-1", "100001"}) {
        const CliRun r = run_cli("render " + scene.string() + " -o " + (dir / "out").string() +
                                 " -q --max-bounces " + bad);
        EXPECT_EQ(r.exit_code, 2) << r.out;
        EXPECT_NE(r.out.find("--max-bounces: expected 0–100000"), std::string::npos) << r.out;
    }
}

// --estimator chooses the reflection estimator (scene file: sampling.estimator); the EXR header
// records it; an unknown name is a usage error naming the option and the accepted values.
TEST(Cli, RenderEstimatorIsValidatedAndRecorded) {
    const tirpol::test::TempDir dir;
    const auto scene = tirpol::test::source_dir() / "config" / "scenes" / "panels_night.yaml";
    const std::string render =
        "render " + scene.string() + " -o " + (dir / "out").string() + " -q ";
    const CliRun bad = run_cli(render + "--estimator mcmc");
    EXPECT_EQ(bad.exit_code, 2) << bad.out;
    EXPECT_NE(bad.out.find("--estimator: expected plain or control-variate, got 'mcmc'"),
              std::string::npos)
        << bad.out;
    for (const char* estimator : {"plain", "control-variate"}) {
        const CliRun r = run_cli(render + "--width 8 --height 6 --spp 2 --estimator " + estimator);
        ASSERT_EQ(r.exit_code, 0) << r.out;
        const auto header = tirpol::read_exr(dir / "out" / "panels_night.exr").attributes();
        EXPECT_EQ(std::get<std::string>(header.at("estimator")), estimator);
    }
}
