// Outputs never replace inputs (docs/cli.md), for every subcommand: each one that writes is run
// with an output that is one of its inputs (or, for folder outputs, a folder holding a user's file
// under a name it writes) and must exit 2 naming both paths, leaving the file as it was; each one
// that writes nothing says so. A subcommand listed by `tirpol --help` without a row fails the test,
// so a new command cannot skip the check. Then the reported cases one by one, and the sweep
// folder's lock.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <map>
#include <set>
#include <sstream>

#include "cli_runner.h"
#include "test_support.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/output_guard.h"

namespace {

namespace fs = std::filesystem;
using testing::HasSubstr;
using tirpol::test::CliRun;
using tirpol::test::run_cli;
using tirpol::test::subcommands_in_help;

struct Row {
    std::string args;  ///< after `tirpol <subcommand>`: an output onto an input or a user's file
    fs::path protected_file;  ///< must be named and unchanged
    bool takes_force = true;  ///< has --force (acquire's session writer has its own rule)
};

class OutputGuardCli : public testing::Test {
protected:
    void SetUp() override {
        // Inputs: only their existence matters, the check runs before any is read.
        tirpol::test::write_text(session() / "session.json", "{\"the\": \"manifest\"}\n");
        for (const char* f :
             {"cal.exr", "m.csv", "frame.png", "rois.yaml", "plan.yaml", "points.csv", "cam.yaml",
              "thermal.yaml", "material.yaml", "measured.exr", "simulated.exr"})
            tirpol::test::write_text(dir_ / f, std::string("input ") + f + "\n");
        tirpol::test::write_text(dir_ / "stack" / "f0.exr", "frame\n");
        tirpol::test::write_text(dir_ / "render-out" / "ball_on_snow_night.exr",
                                 "the user's EXR\n");
        tirpol::test::write_text(dir_ / "sweep-out" / "results.csv", "the user's table\n");
        tirpol::test::write_text(dir_ / "demo-out" / "calibration", "the user's notes\n");
        tirpol::test::write_text(dir_ / "compare-out" / "comparison.exr", "the measured image\n");
        tirpol::test::write_text(dir_ / "sweep.yaml",
                                 "scene: " + scene() +
                                     "\nset:\n  camera.resolution: [32, 24]\n  sampling.spp: 4\n"
                                     "axes:\n  camera.fov_deg: [20, 30]\n");
    }
    std::string p(const std::string& name) const { return (dir_ / name).string(); }
    fs::path session() const { return dir_ / "session"; }
    static std::string scene() {
        return (tirpol::test::source_dir() / "config/scenes/ball_on_snow_night.yaml").string();
    }
    tirpol::test::TempDir dir_;
};

TEST_F(OutputGuardCli, EveryWritingSubcommandRefusesToReplaceAnInputWithExitTwo) {
    const std::string manifest = (session() / "session.json").string();
    const std::map<std::string, Row> writing = {
        {"acquire",
         {p("plan.yaml") + " --camera sim:// --stage sim:// -o " + p("plan.yaml"), p("plan.yaml"),
          false}},
        {"calibrate radiometric", {session().string() + " -o " + manifest, manifest}},
        {"calibrate microgrid", {session().string() + " -o " + manifest, manifest}},
        {"calibrate polarimetric",
         {session().string() + " --calibration " + p("cal.exr") + " -o " + p("cal.exr"),
          p("cal.exr")}},
        {"calibrate geometric",
         {p("frame.png") + " --target checkerboard:9x6:0.02 -o " + p("frame.png"), p("frame.png")}},
        {"calibrate pose",
         {"--camera " + p("cam.yaml") + " --points " + p("points.csv") + " -o " + p("points.csv"),
          p("points.csv")}},
        {"compare",
         {"--measured " + p("compare-out/comparison.exr") + " --simulated " + p("simulated.exr") +
              " -o " + p("compare-out"),
          p("compare-out/comparison.exr")}},
        {"demo", {"-o " + p("demo-out"), p("demo-out/calibration")}},
        {"demosaic", {p("frame.png") + " -o " + p("frame.png"), p("frame.png")}},
        {"emissivity",
         {p("material.yaml") + " --wavelength-um 10 --angles-deg 0,30 --csv " + p("material.yaml"),
          p("material.yaml")}},
        {"extract-emissivity",
         {p("measured.exr") + " " + p("rois.yaml") + " -o " + p("rois.yaml"), p("rois.yaml")}},
        {"fit", {p("m.csv") + " -o " + p("m.csv"), p("m.csv")}},
        {"flir-temperature",
         {p("frame.png") + " --planck 1,2,3,4,5 -o " + p("frame.png"), p("frame.png")}},
        {"noise", {p("stack") + " -o " + p("stack/report.json"), p("stack")}},
        {"live",
         {"--camera sim://uniform --calibration " + p("cal.exr") + " --snapshot-dir " +
              p("cal.exr"),
          p("cal.exr")}},
        {"reduce",
         {session().string() + " --calibration " + p("cal.exr") + " -o " + manifest, manifest}},
        {"render", {scene() + " -o " + p("render-out"), p("render-out/ball_on_snow_night.exr")}},
        {"sweep", {p("sweep.yaml") + " -o " + p("sweep-out"), p("sweep-out/results.csv")}},
        {"temperature",
         {p("frame.png") + " --calibration " + p("cal.exr") + " -o " + p("frame.png"),
          p("frame.png")}},
        {"therm", {p("thermal.yaml") + " --csv " + p("thermal.yaml"), p("thermal.yaml")}},
    };
    // Subcommands that write no file, and why.
    const std::map<std::string, std::string> not_writing = {
        {"brdf", "prints"},    {"calibrate", "a group"},
        {"devices", "prints"}, {"fit-render", "prints the fitted parameters"},
        {"info", "prints"},    {"planck", "prints"},
        {"sun", "prints"},
    };
    std::set<std::string> listed = subcommands_in_help("");
    for (const auto& nested : subcommands_in_help("calibrate")) listed.insert(nested);
    ASSERT_GE(listed.size(), 20u) << "could not read the subcommands from tirpol --help";
    for (const auto& name : listed)
        EXPECT_TRUE(writing.count(name) + not_writing.count(name) == 1)
            << "'" << name << "' needs exactly one row: what it writes, or why it writes nothing";

    for (const auto& [command, row] : writing) {
        const bool folder = fs::is_directory(row.protected_file);
        const std::string before = folder ? "" : tirpol::read_file(row.protected_file);
        const CliRun r = run_cli(command + " " + row.args);
        EXPECT_EQ(r.exit_code, 2) << "tirpol " << command << " " << row.args << "\n" << r.out;
        EXPECT_THAT(r.out, HasSubstr(row.protected_file.string()))
            << "tirpol " << command << " " << row.args;
        if (!folder) {
            EXPECT_EQ(tirpol::read_file(row.protected_file), before) << command;
        }
        if (row.takes_force) {
            EXPECT_THAT(run_cli(command + " --help").out, HasSubstr("--force")) << command;
        }
        // An input is never replaced, --force or not.
        if (row.takes_force && row.protected_file.string().find("-out") == std::string::npos) {
            const CliRun forced = run_cli(command + " " + row.args + " --force");
            EXPECT_EQ(forced.exit_code, 2)
                << "tirpol " << command << " " << row.args << " --force\n"
                << forced.out;
        }
    }
}

TEST_F(OutputGuardCli, TheReportedCases) {
    // reduce S --calibration C -o S/session.json replaced the manifest with an EXR, exit 0.
    const std::string manifest = (session() / "session.json").string();
    CliRun r = run_cli("reduce " + session().string() + " --calibration " + p("cal.exr") + " -o " +
                       manifest);
    EXPECT_EQ(r.exit_code, 2) << r.out;
    EXPECT_THAT(r.out,
                HasSubstr("--output " + manifest + ": lies inside the input folder SESSION (" +
                          session().string() + ")"));
    EXPECT_EQ(tirpol::read_file(manifest), "{\"the\": \"manifest\"}\n");
    // Another spelling, a symlink and a hard link of the measurement: the same file.
    fs::create_symlink(dir_ / "m.csv", dir_ / "link.csv");
    fs::create_hard_link(dir_ / "m.csv", dir_ / "hard.csv");
    for (const std::string& out : {p("stack/../m.csv"), p("link.csv"), p("hard.csv")}) {
        r = run_cli("fit " + p("m.csv") + " -o " + out);
        EXPECT_EQ(r.exit_code, 2) << out << "\n" << r.out;
        EXPECT_THAT(r.out, HasSubstr("is the input DATA (" + p("m.csv") + ")")) << out;
    }
    EXPECT_EQ(tirpol::read_file(dir_ / "m.csv"), "input m.csv\n");
    // An existing file that is not an input: only with --force.
    r = run_cli("temperature " + p("frame.png") + " --calibration " + p("cal.exr") + " -o " +
                p("measured.exr"));
    EXPECT_EQ(r.exit_code, 2) << r.out;
    EXPECT_THAT(r.out, HasSubstr("pass --force to replace it"));
    r = run_cli("temperature " + p("frame.png") + " --calibration " + p("cal.exr") + " -o " +
                p("measured.exr") + " --force");
    EXPECT_EQ(r.exit_code, 1) << "past the check, the (fake) calibration is read and refused\n"
                              << r.out;
    // render -o afile rendered, then failed on create_directories: now refused before the work.
    r = run_cli("render " + scene() + " -o " + p("cal.exr") + " --width 8 --height 6 --spp 1");
    EXPECT_EQ(r.exit_code, 2) << r.out;
    EXPECT_THAT(r.out, HasSubstr(p("cal.exr") + ": exists and is not a folder"));
    EXPECT_THAT(r.out, testing::Not(HasSubstr("rendered")));
}

TEST_F(OutputGuardCli, ASweepFolderKeepsTheUsersFilesAndIsLockedByOneRun) {
    const std::string sweep = p("sweep.yaml"), out = p("sweep-out");
    CliRun r = run_cli("sweep " + sweep + " -o " + out + " -q");
    EXPECT_EQ(r.exit_code, 2) << r.out;
    EXPECT_THAT(
        r.out,
        HasSubstr(out +
                  "/results.csv, which this command would replace and no tirpol command wrote"));
    EXPECT_EQ(tirpol::read_file(dir_ / "sweep-out" / "results.csv"), "the user's table\n");
    EXPECT_FALSE(fs::exists(dir_ / "sweep-out" / "manifest.json"))
        << "nothing rendered before the check";

    // A fresh folder: the sweep claims what it writes, so --resume into it is not refused.
    const std::string fresh = p("fresh-sweep");
    r = run_cli("sweep " + sweep + " -o " + fresh + " -q");
    ASSERT_EQ(r.exit_code, 0) << r.out;
    r = run_cli("sweep " + sweep + " -o " + fresh + " --resume -q");
    EXPECT_EQ(r.exit_code, 0) << r.out;
    EXPECT_THAT(r.out, HasSubstr("0 rendered, 2 resumed"));

    // While another run holds the folder, a second --resume exits 1 naming the holder's pid.
    {
        const tirpol::FolderLock held(fresh, "this test");
        r = run_cli("sweep " + sweep + " -o " + fresh + " --resume -q");
        EXPECT_EQ(r.exit_code, 1) << r.out;
        EXPECT_THAT(r.out,
                    HasSubstr(fresh + " is in use by process " + std::to_string(::getpid())));
    }
}

}  // namespace
