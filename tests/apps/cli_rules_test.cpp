// The rules every subcommand follows (docs/cli.md): --version, exit code 2 for usage errors with a
// "did you mean" for misspelt subcommands and options, -o/--output for what a command writes,
// list-valued options as "8 14" or "8,14", library material names where files are accepted, and
// nothing on stderr from the libraries underneath.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <regex>

#include "cli_runner.h"
#include "test_support.h"
#include "tirpol/core/atomic_file.h"

namespace {

using tirpol::test::CliRun;
using tirpol::test::run_cli;

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

TEST(CliRules, VersionPrintsTheProjectVersion) {
    const CliRun r = run_cli("--version");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_TRUE(std::regex_match(r.out, std::regex("tirpol [0-9]+\\.[0-9]+\\.[0-9]+\n"))) << r.out;
}

TEST(CliRules, MisspeltSubcommandExitsTwoWithASuggestion) {
    const CliRun r = run_cli("rendr scene.yaml");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.out, "did you mean 'render'?")) << r.out;
    // The hint comes first and alone: not after CLI11's "A subcommand is required", which would be
    // wrong (one was given, misspelt).
    EXPECT_EQ(r.out.rfind("tirpol: unknown subcommand 'rendr'", 0), 0u) << r.out;
    EXPECT_FALSE(contains(r.out, "A subcommand is required")) << r.out;
    const CliRun far = run_cli("xyzzy");
    EXPECT_EQ(far.exit_code, 2);
    EXPECT_FALSE(contains(far.out, "did you mean")) << far.out;  // nothing close: no guess
}

TEST(CliRules, MisspeltOptionExitsTwoWithASuggestion) {
    CliRun r = run_cli("planck --temperture-k 300 --band-um 8 14");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.out, "did you mean '--temperature-k'?")) << r.out;
    r = run_cli("compare --measured a.exr --simulated b.exr --ouput r");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.out, "did you mean '--output'?")) << r.out;
}

TEST(CliRules, ListOptionsAcceptSpacesOrCommas) {
    const CliRun spaced = run_cli("planck --temperature-k 300 --band-um 8 14 --json", false);
    const CliRun commas = run_cli("planck --temperature-k 300 --band-um 8,14 --json", false);
    ASSERT_EQ(spaced.exit_code, 0) << spaced.out;
    ASSERT_EQ(commas.exit_code, 0) << commas.out;
    EXPECT_EQ(nlohmann::json::parse(spaced.out), nlohmann::json::parse(commas.out));
    EXPECT_EQ(run_cli("planck --temperature-k 300 --band-um 8,14,20").exit_code, 2);
}

TEST(CliRules, EveryCommandThatWritesTakesDashOOutput) {
    for (const char* sub : {"acquire", "calibrate radiometric", "calibrate polarimetric", "reduce",
                            "render", "compare", "fit", "extract-emissivity", "noise",
                            "temperature", "flir-temperature", "demo"}) {
        const CliRun r = run_cli(std::string(sub) + " --help");
        EXPECT_EQ(r.exit_code, 0) << sub;
        EXPECT_TRUE(contains(r.out, "-o,--output")) << sub << ":\n" << r.out;
        EXPECT_FALSE(contains(r.out, "--out ")) << sub;  // the old render spelling is hidden
    }
}

TEST(CliRules, RenderWithoutOutputIsAUsageError) {
    const std::string scene =
        (tirpol::test::source_dir() / "config/scenes/panels_night.yaml").string();
    const CliRun r = run_cli("render " + scene);
    EXPECT_EQ(r.exit_code, 2) << r.out;
    EXPECT_TRUE(contains(r.out, "--output")) << r.out;
    // --out and --output together are one option given twice: usage error.
    EXPECT_EQ(run_cli("render " + scene + " --out a --output b").exit_code, 2);
}

TEST(CliRules, LibraryMaterialNamesWorkWhereMaterialFilesDo) {
    const std::string file =
        (tirpol::test::source_dir() / "config/materials/flat_black_paint.yaml").string();
    const std::string rest = " --wavelength-um 10 --angles-deg 0,60 --json";
    const CliRun by_file = run_cli("emissivity " + file + rest, false);
    const CliRun by_name = run_cli("emissivity flat_black_paint" + rest, false);
    ASSERT_EQ(by_file.exit_code, 0) << by_file.out;
    ASSERT_EQ(by_name.exit_code, 0) << by_name.out;
    auto jf = nlohmann::json::parse(by_file.out), jn = nlohmann::json::parse(by_name.out);
    jf.erase("material_file");
    jn.erase("material_file");
    EXPECT_EQ(jf["angles"], jn["angles"]);
    const CliRun brdf = run_cli(
        "brdf flat_black_paint --wavelength-um 10 --incident-deg 30,0 --exitant-deg 30,180");
    EXPECT_EQ(brdf.exit_code, 0) << brdf.out;
    const CliRun typo = run_cli("emissivity flat_blak_paint" + rest);
    EXPECT_EQ(typo.exit_code, 1);
    EXPECT_TRUE(contains(typo.out, "did you mean 'flat_black_paint'?")) << typo.out;
}

TEST(CliRules, NoLibraryNoiseOnStderr) {
    // A Ceres fit (glog underneath) and a render (OpenCV PNG quicklooks): stderr carries nothing
    // but our own lines — no glog preamble, no OpenCV info, no spdlog timestamps.
    tirpol::test::TempDir dir;
    tirpol::test::write_text(
        dir / "eps.csv",
        "angle_deg,e_s0,e_s0_sigma,e_s1,e_s1_sigma\n"
        "0,0.962,0.003,0.000,0.002\n20,0.961,0.003,0.0012,0.002\n40,0.957,0.003,0.0060,0.002\n"
        "60,0.940,0.003,0.0190,0.002\n70,0.915,0.003,0.0330,0.002\n80,0.840,0.003,0.0560,0.002\n");
    const std::string cmd = std::string(TIRPOL_CLI_PATH) + " fit " + (dir / "eps.csv").string() +
                            " --wavelength-um 10 --starts 2 -o " + (dir / "fit.yaml").string() +
                            " >/dev/null 2>" + (dir / "stderr.txt").string();
    const int status = std::system(cmd.c_str());
    const std::string err = tirpol::read_file(dir / "stderr.txt");
    EXPECT_FALSE(contains(err, "InitGoogleLogging")) << err;
    EXPECT_FALSE(contains(err, "[info]")) << err;
    for (const char* glog_prefix : {"\nI20", "\nW20", "\nE20"})
        EXPECT_FALSE(contains("\n" + err, glog_prefix)) << err;
    EXPECT_EQ(WEXITSTATUS(status), 0) << err;
}

TEST(CliRules, ReadingAPngWithChunksLibpngWarnsAboutPrintsNothingOnStderr) {
    // tests/core/raw_png_test.cpp checks that OpenCV's decoder makes libpng warn on this file.
    tirpol::test::TempDir dir;
    const auto png = tirpol::test::source_dir() /
                     "tests/data/fuzz-regressions/raw_image/ancillary_chunk_warnings.png";
    const std::string cmd = std::string(TIRPOL_CLI_PATH) + " flir-temperature " + png.string() +
                            " --planck 21106.77,0.012545258,1501,1,-7340 -o " +
                            (dir / "t.exr").string() + " >/dev/null 2>" +
                            (dir / "stderr.txt").string();
    const int status = std::system(cmd.c_str());
    const std::string err = tirpol::read_file(dir / "stderr.txt");
    EXPECT_EQ(WEXITSTATUS(status), 0) << err;
    EXPECT_EQ(err, "");
}

}  // namespace
