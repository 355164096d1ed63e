// The one numeric-option parser (core/src/option_values.cpp, applied by
// apps/tirpol/numeric_options.cpp), checked over every option of
// every subcommand as `tirpol ... --help` lists them: an option shown as FLOAT, INT or UINT refuses
// nan and inf with exit 2 and a message naming it, and an option of the limits table refuses a
// value beyond its limit. Options are read from the help, so an option added later is covered by
// this test without editing it. Then the reproducers of the bounds report, each with its new
// behaviour.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "cli_runner.h"
#include "test_support.h"
#include "tirpol/core/limits.h"

namespace {

using tirpol::test::CliRun;
using tirpol::test::run_cli;
using tirpol::test::run_command;
using tirpol::test::subcommands_in_help;
namespace limits = tirpol::limits;

struct NumericOption {
    std::string name;  ///< --long-name
    int values;        ///< values it takes at once (FLOAT x 2 → 2)
};

/// The options of `tirpol PATH --help` whose type CLI11 shows as FLOAT, INT or UINT.
std::vector<NumericOption> numeric_options_in_help(const std::string& path) {
    const CliRun help = run_cli(path + " --help", false);
    static const std::regex option(R"(^\s+(?:-\w,)?(--[\w-]+)\s+(?:FLOAT|INT|UINT)(?: x (\d+))?)");
    std::vector<NumericOption> out;
    std::istringstream lines(help.out);
    for (std::string line; std::getline(lines, line);) {
        std::smatch m;
        if (std::regex_search(line, m, option))
            out.push_back({m[1], m[2].matched ? std::stoi(m[2]) : 1});
    }
    return out;
}

// `--name=V,V,...`: one argument, so a value cannot be taken for a missing positional argument.
std::string option_with(const std::string& name, const std::string& value, int times) {
    std::string out = name + "=";
    for (int i = 0; i < times; ++i) out += (i ? "," : "") + value;
    return out;
}

std::vector<std::string> all_commands() {
    std::vector<std::string> commands;
    for (const auto& name : subcommands_in_help("")) {
        const auto nested = subcommands_in_help(name);
        if (nested.empty()) commands.push_back(name);
        commands.insert(commands.end(), nested.begin(), nested.end());
    }
    return commands;
}

TEST(NumericOptions, EveryNumericOptionOfEverySubcommandRefusesNanAndInfinity) {
    std::size_t checked = 0;
    for (const std::string& command : all_commands()) {
        for (const NumericOption& o : numeric_options_in_help(command)) {
            for (const std::string bad : {"nan", "inf", "1e400"}) {
                const std::string args = command + " " + option_with(o.name, bad, o.values);
                const CliRun r = run_cli(args);
                EXPECT_EQ(r.exit_code, 2) << "tirpol " << args << "\n" << r.out;
                EXPECT_THAT(r.out, testing::HasSubstr(o.name + ": expected a finite number"))
                    << "tirpol " << args;
            }
            ++checked;
        }
    }
    // planck, render, fit, sun, flir-temperature, emissivity, brdf, … have dozens between them.
    EXPECT_GE(checked, 40u) << "could not read the numeric options from the subcommands' --help";
}

TEST(NumericOptions, OptionsOfTheLimitsTableRefuseValuesBeyondTheirLimit) {
    // Value beyond the limit, per option name, from core/limits.h (docs/cli.md, "Limits table").
    const std::map<std::string, std::string> beyond = {
        {"--band-um", "1e7"},
        {"--wavelength-um", "0.001"},
        {"--temperature-k", "20000"},
        {"--fpa-temperature-k", "0.5"},
        {"--spp", std::to_string(limits::kMaxSamplesPerPixel + 1)},
        {"--width", std::to_string(limits::kMaxImageSide + 1)},
        {"--height", std::to_string(limits::kMaxImageSide + 1)},
        {"--starts", std::to_string(limits::kMaxFitStarts + 1)},
        {"--frames-per-angle", std::to_string(limits::kMaxFramesPerStep + 1)},
    };
    std::set<std::string> seen;
    for (const std::string& command : all_commands()) {
        for (const NumericOption& o : numeric_options_in_help(command)) {
            const auto it = beyond.find(o.name);
            if (it == beyond.end()) continue;
            const std::string args = command + " " + option_with(o.name, it->second, o.values);
            const CliRun r = run_cli(args);
            EXPECT_EQ(r.exit_code, 2) << "tirpol " << args << "\n" << r.out;
            EXPECT_THAT(r.out, testing::HasSubstr(o.name + ": ")) << "tirpol " << args;
            EXPECT_THAT(r.out, testing::HasSubstr("is outside")) << "tirpol " << args << "\n"
                                                                 << r.out;
            seen.insert(o.name);
        }
    }
    for (const auto& [name, value] : beyond)
        EXPECT_TRUE(seen.count(name)) << name << " is in no subcommand's help";
}

// The reproducers of the bounds report: each ends in a usage error naming the option (exit 2) or an
// error naming the file (exit 1), never in an allocation of gigabytes, a hang or NaN output.
TEST(NumericOptions, ReportedReproducersEndInAClearError) {
    const auto source = tirpol::test::source_dir();
    const std::string scene = (source / "config/scenes/ball_on_snow_night.yaml").string();
    const std::string png =
        (source / "tests/data/fuzz-regressions/raw_image/ancillary_chunk_warnings.png").string();
    tirpol::test::TempDir dir;
    const std::string out = (dir.path() / "out").string();
    struct Case {
        std::string args, message;
    };
    const std::vector<Case> cases = {
        {"planck --temperature-k 300 --band-um 0.001 1e7",
         "--band-um: 0.001 is outside [0.1, 1000]"},
        {"planck --temperature-k 300 --band-um 1 1e300", "--band-um: 1e300 is outside [0.1, 1000]"},
        {"render " + scene + " -o " + out + " --spp 2147483647 --width 2 --height 2",
         "--spp: 2147483647 is outside"},
        {"fit " + png + " --starts 10000000 -o " + out + ".yaml",
         "--starts: 10000000 is outside [1, 10000]"},
        {"sun --lat nan --lon 0 --time 2026-01-01T12:00Z",
         "--lat: expected a finite number, got 'nan'"},
        {"sun --lat 39 --lon -105 --time 2026-01-01T12:00Z --tilt-deg nan",
         "--tilt-deg: expected a finite number"},
        {"emissivity flat_black_paint --wavelength-um nan --angles-deg 0:90:10",
         "--wavelength-um: expected a finite"},
        {"emissivity flat_black_paint --wavelength-um 10 --angles-deg 0:90:nan", "--angles-deg"},
        {"brdf flat_black_paint --wavelength-um 10 --incident-deg nan 0 --exitant-deg 30 0",
         "--incident-deg: expected a finite number"},
        {"flir-temperature " + png + " --planck 17096,0.046,1428,1,-342 --emissivity 1e-300 -o " +
             out + ".exr",
         "--emissivity: 1e-300 is outside [0.01, 1]"},
        {"fit " + png + " --bound sigma=0.05:nan -o " + out + ".yaml",
         "expected a finite number, got 'nan'"},
    };
    for (const Case& c : cases) {
        const CliRun r = run_cli(c.args);
        EXPECT_EQ(r.exit_code, 2) << "tirpol " << c.args << "\n" << r.out;
        EXPECT_THAT(r.out, testing::HasSubstr(c.message)) << "tirpol " << c.args;
    }
    EXPECT_FALSE(std::filesystem::exists(out + ".exr")) << "flir-temperature wrote an output";
}

TEST(NumericOptions, ASessionManifestThatIsADeviceOrAFifoIsRefusedWithoutReadingOrBlocking) {
    tirpol::test::TempDir dir;
    const auto zero = dir.path() / "zero";
    const auto fifo = dir.path() / "fifo";
    std::filesystem::create_directories(zero);
    std::filesystem::create_directories(fifo);
    std::filesystem::create_symlink("/dev/zero", zero / "session.json");
    ASSERT_EQ(::mkfifo((fifo / "session.json").c_str(), 0600), 0);
    // `timeout` turns a hang into a failure of this test rather than of the whole suite.
    const std::string cli = std::string("timeout 60 ") + TIRPOL_CLI_PATH;
    const CliRun z = run_command(cli + " calibrate radiometric " + zero.string() + " -o " +
                                 (dir / "c.exr").string());
    EXPECT_EQ(z.exit_code, 1) << z.out;
    EXPECT_THAT(z.out, testing::HasSubstr("session.json: is a character device"));
    const CliRun f = run_command(cli + " calibrate radiometric " + fifo.string() + " -o " +
                                 (dir / "c.exr").string());
    EXPECT_EQ(f.exit_code, 1) << f.out;
    EXPECT_THAT(f.out, testing::HasSubstr("session.json: is a FIFO"));
}

}  // namespace
