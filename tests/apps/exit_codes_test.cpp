// The exit-code rule of docs/cli.md, checked for every subcommand: a command line that is wrong in
// itself (unknown option, missing or extra argument, malformed value, value outside an option's
// range, options that conflict or need each other) exits 2 with a message and "Run with --help";
// errors found in files, devices or results exit 1. One row per subcommand; a subcommand listed by
// `tirpol --help` without a row fails the test, so a new command cannot skip the audit.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <sstream>

#include "cli_runner.h"
#include "test_support.h"

namespace {

using tirpol::test::CliRun;
using tirpol::test::run_cli;
using tirpol::test::subcommands_in_help;

struct BadUsage {
    std::string args;     ///< after `tirpol <subcommand>`
    std::string message;  ///< part of what the user must be told
};

TEST(ExitCodes, EverySubcommandExitsTwoOnBadUsageWithAMessage) {
    const auto data = tirpol::test::source_dir() / "tests/data/fuzz-regressions";
    const std::string exr = (data / "exr/non_utf8_attribute.exr").string();
    const std::string png = (data / "raw_image/ancillary_chunk_warnings.png").string();
    const std::string scene =
        (tirpol::test::source_dir() / "config/scenes/ball_on_snow_night.yaml").string();
    const std::string thermal =
        (tirpol::test::source_dir() / "config/thermal/ball_on_snow_thermal.yaml").string();
    tirpol::test::TempDir dir;
    const std::string session =
        dir.path().string();  // an (empty) directory where a session is expected
    const std::map<std::string, BadUsage> rows = {
        {"acquire", {"--camera sim://", "required"}},
        {"brdf",
         {"flat_black_paint --wavelength-um 10 --incident-deg 95 0 --exitant-deg 30 0",
          "--incident-deg"}},
        {"calibrate", {"", "subcommand"}},
        {"calibrate radiometric", {session + " -o c.exr --no-such-option", "no-such-option"}},
        {"calibrate polarimetric",
         {session + " --calibration " + exr + " -o p.yaml --axis-offset-deg 1",
          "--extinction-ratio"}},
        {"calibrate geometric", {png + " --target checkerboard:9x6 -o cam.yaml", "--target"}},
        {"calibrate pose", {"--camera " + exr, "required"}},
        {"calibrate microgrid", {session + " --band-um 14 8 -o m.exr", "--band-um"}},
        {"compare",
         {"--measured " + exr + " --simulated " + exr + " --registration sideways -o r",
          "--registration"}},
        {"demo", {"--no-such-option", "no-such-option"}},
        {"demosaic", {png + " --pattern sony --method cubic -o d.exr", "--method"}},
        {"devices", {"surplus-argument", "surplus-argument"}},
        {"emissivity",
         {"flat_black_paint --wavelength-um 10 --angles-deg 0:100:10", "--angles-deg"}},
        {"extract-emissivity", {session + " " + png + " -o e.csv", "--calibration"}},
        {"fit", {exr + " --wavelength-um 10 --model lambertian -o f.yaml", "--model"}},
        {"fit-render",
         {scene + " --view " + exr + " --region ball --free glossy_black_paint.n=1.2", "--free"}},
        {"flir-temperature", {png + " --planck 1,2,3 -o t.exr", "--planck"}},
        {"info", {"", "required"}},
        {"live", {"", "--camera"}},
        {"noise", {"-o n.json", "required"}},
        {"planck", {"--temperature-k 300 --band-um 14 8", "--band-um"}},
        {"reduce", {session + " -o s.exr --slar", "--slar"}},
        {"render", {scene + " -o out --spp 0", "--spp"}},
        {"sun", {"--lat 39 --lon -105 --time 2003-10-17T12:30", "has no UTC offset"}},
        {"sweep", {"-o out", "required"}},
        {"temperature", {png + " -o t.exr", "--calibration"}},
        {"therm", {thermal + " --at 2026-01-16T25:00", "--at"}},
    };
    std::set<std::string> listed = subcommands_in_help("");
    for (const auto& nested : subcommands_in_help("calibrate")) listed.insert(nested);
    ASSERT_GE(listed.size(), 20u) << "could not read the subcommands from tirpol --help";
    for (const auto& name : listed)
        EXPECT_TRUE(rows.count(name)) << "no bad-usage row for '" << name << "'";

    for (const auto& [command, bad] : rows) {
        const CliRun r = run_cli(command + " " + bad.args);
        EXPECT_EQ(r.exit_code, 2) << "tirpol " << command << " " << bad.args << "\n" << r.out;
        EXPECT_THAT(r.out, testing::HasSubstr(bad.message))
            << "tirpol " << command << " " << bad.args;
        EXPECT_THAT(r.out, testing::HasSubstr("--help")) << "tirpol " << command << " " << bad.args;
        // And an unknown option, the commonest slip, on every subcommand.
        const CliRun unknown = run_cli(command + " --definitely-not-an-option");
        EXPECT_EQ(unknown.exit_code, 2) << "tirpol " << command << " --definitely-not-an-option\n"
                                        << unknown.out;
    }
}

TEST(ExitCodes, FitRenderKeepsTheCommasOfOneViewTogether) {
    // `--view STOKES.exr,CAMERA.yaml,POSE.yaml` is one view of three files (docs/fitting.md), not
    // three views: a two-file view must be refused as a malformed view, before any file is read.
    const std::string scene =
        (tirpol::test::source_dir() / "config/scenes/ball_on_snow_night.yaml").string();
    const CliRun r = run_cli("fit-render " + scene +
                             " --view /nonexistent/a.exr,/nonexistent/cam.yaml --region ball"
                             " --free glossy_black_paint.n=1.2:1.8");
    EXPECT_EQ(r.exit_code, 2) << r.out;
    EXPECT_THAT(r.out, testing::HasSubstr("expected MEASURED.exr or")) << r.out;
}

TEST(ExitCodes, ErrorsInFilesExitOne) {
    // The command line is right; what it names is not: a missing file, a file of the wrong kind.
    const auto data = tirpol::test::source_dir() / "tests/data/fuzz-regressions";
    EXPECT_EQ(run_cli("info /nonexistent/file.exr").exit_code, 1);
    // One rule for a missing input whichever subcommand names it (docs/cli.md: exit 1), whether the
    // subcommand opens the file itself (info) or has its option checked while parsing (CLI11's
    // ExistingFile): the message names the path.
    for (const std::string& line :
         {std::string("render /nonexistent/scene.yaml -o out"),
          std::string("compare --measured /nonexistent/m.exr --simulated /nonexistent/s.exr -o r"),
          std::string("fit /nonexistent/curve.csv")}) {
        const CliRun r = run_cli(line);
        EXPECT_EQ(r.exit_code, 1) << "tirpol " << line << "\n" << r.out;
        EXPECT_THAT(r.out, testing::HasSubstr("/nonexistent/")) << r.out;
        EXPECT_THAT(r.out, testing::Not(testing::HasSubstr("--help"))) << r.out;
    }
    const CliRun huge = run_cli("info " + (data / "exr/attribute_declares_1_6_GB.exr").string());
    EXPECT_EQ(huge.exit_code, 1) << huge.out;
    EXPECT_THAT(huge.out, testing::HasSubstr("declares 1634231040 bytes"));
}

}  // namespace
