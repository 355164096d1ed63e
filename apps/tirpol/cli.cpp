#include "cli.h"

#include <fmt/format.h>
#include <glog/logging.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <opencv2/core/utils/logger.hpp>

#include "invocation.h"
#include "numeric_options.h"
#include "tirpol/core/config.h"
#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/log.h"
#include "tirpol/report/provenance.h"
#include "tirpol/twin/scene_camera.h"

namespace tirpol::cli {

namespace {
std::vector<std::pair<int, CommandRegistration>>& registry() {
    static std::vector<std::pair<int, CommandRegistration>> r;
    return r;
}

std::string& command_line_storage() {
    static std::string line;
    return line;
}

// Libraries under the CLI write to stderr on their own: glog (through Ceres) warns "Logging before
// InitGoogleLogging" and would log to files in /tmp once initialised; OpenCV prints info lines.
// Route them to stderr at the level the user asked for, and give spdlog a plain "tirpol: level:
// message" pattern (timestamps only when debugging).
void quiet_libraries(const char* argv0, const std::string& log_level) {
    const bool debugging = log_level == "debug" || log_level == "trace";
    FLAGS_logtostderr = true;
    FLAGS_minloglevel = debugging ? google::GLOG_INFO : google::GLOG_ERROR;
    if (!google::IsGoogleLoggingInitialized()) google::InitGoogleLogging(argv0);
    cv::utils::logging::setLogLevel(debugging ? cv::utils::logging::LOG_LEVEL_INFO
                                              : cv::utils::logging::LOG_LEVEL_ERROR);
    spdlog::set_pattern(debugging ? "[%H:%M:%S.%e] tirpol: %l: %v" : "tirpol: %l: %v");
}

std::vector<std::string> option_names(const CLI::App& app) {
    std::vector<std::string> names;
    for (const CLI::Option* o : app.get_options()) {
        for (const auto& l : o->get_lnames()) names.push_back("--" + l);
        for (const auto& s : o->get_snames()) names.push_back("-" + s);
    }
    return names;
}

std::vector<std::string> subcommand_names(const CLI::App& app) {
    std::vector<std::string> names;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
        names.push_back(sub->get_name());
    return names;
}

// "did you mean" hints for the arguments CLI11 could not place: misspelt subcommands and options.
struct Suggestions {
    std::vector<std::string> lines;
    bool names_a_subcommand = false;  // a misspelt subcommand was recognised ("rendr")
};

Suggestions suggestions_for(CLI::App& app) {
    Suggestions found;
    CLI::App* deepest = &app;
    while (!deepest->get_subcommands().empty()) deepest = deepest->get_subcommands().front();
    for (const std::string& arg : app.remaining(true)) {
        if (arg.rfind('-', 0) == 0 && arg.size() > 1) {
            const std::string name = arg.substr(0, arg.find('='));
            const std::string hint = closest_match(name, option_names(*deepest));
            if (!hint.empty())
                found.lines.push_back(
                    fmt::format("tirpol: unknown option '{}' for '{}'; did you mean '{}'?", name,
                                deepest == &app ? "tirpol" : deepest->get_name(), hint));
        } else if (deepest->get_subcommands([](const CLI::App*) { return true; }).size() > 0) {
            const std::string hint = closest_match(arg, subcommand_names(*deepest));
            if (!hint.empty()) {
                found.lines.push_back(
                    fmt::format("tirpol: unknown subcommand '{}'; did you mean '{}'?", arg, hint));
                found.names_a_subcommand = true;
            }
        }
    }
    return found;
}

// CLI11's messages for a path that is not there ("--measured: File does not exist: a.exr").
bool names_a_missing_path(const std::string& message) {
    return message.find("File does not exist") != std::string::npos ||
           message.find("Directory does not exist") != std::string::npos ||
           message.find("Path does not exist") != std::string::npos;
}

// A command line wrong in itself: CLI11's message (unless a misspelt subcommand explains it), the
// did-you-mean hints, exit 2.
int usage_error(CLI::App& app, const CLI::ParseError& e) {
    const Suggestions hints = suggestions_for(app);
    // A misspelt subcommand is the whole story: CLI11's "A subcommand is required" (the misspelling
    // was not taken for one) would only mislead before the hint.
    if (!hints.names_a_subcommand) app.exit(e);
    for (const std::string& line : hints.lines) std::fprintf(stderr, "%s\n", line.c_str());
    if (hints.names_a_subcommand) std::fprintf(stderr, "Run with --help for more information.\n");
    return kExitUsage;
}

// List-valued options take "8 14" and "8,14" alike, everywhere.
void accept_comma_lists(CLI::App& app) {
    for (CLI::Option* o : app.get_options())
        if (o->get_expected_max() > 1 && o->get_delimiter() == '\0') o->delimiter(',');
    for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
        accept_comma_lists(*sub);
}
}  // namespace

std::string version_text() { return std::string("tirpol ") + TIRPOL_VERSION; }

const std::string& command_line_text() { return command_line_storage(); }

bool register_command(int order, CommandRegistration registration) {
    registry().emplace_back(order, std::move(registration));
    return true;
}

int run(int argc, char** argv) {
    command_line_storage() = report::quoted_command_line(argc, argv);
    quiet_libraries(argv[0], "info");
    twin::register_twin_device_schemes();  // `--camera sim://<scene.yaml>` wherever a camera URI is
                                           // taken
    CLI::App app{"tirpol — thermal-infrared polarimetry with the instrument in the loop"};
    app.require_subcommand(1);
    app.set_version_flag("--version", version_text());
    app.footer(
        "Exit codes: 0 success, 1 error in an input, a file or a device, 2 bad command-line usage "
        "(docs/cli.md).");
    std::string log_level = "info";
    app.add_option("--log-level", log_level, "trace, debug, info, warn, error or off")
        ->capture_default_str();
    app.parse_complete_callback([&] {
        set_log_level(log_level);
        quiet_libraries(argv[0], log_level);
    });

    auto& commands = registry();
    std::stable_sort(commands.begin(), commands.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [order, add] : commands) add(app);
    accept_comma_lists(app);
    validate_numeric_options(app);

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ValidationError& e) {
        // CLI11's ExistingFile/ExistingDirectory/ExistingPath checks: the command line is right,
        // the file it names is missing, an error in an input (exit 1), as `info` reports it. CLI11
        // checks files before it rejects unknown arguments: those (still in remaining()) make it
        // a usage error first.
        if (!names_a_missing_path(e.what()) || !app.remaining(true).empty())
            return usage_error(app, e);
        std::fprintf(stderr, "tirpol: error: %s\n", e.what());
        return kExitError;
    } catch (const CLI::ParseError& e) {
        return usage_error(app, e);
    } catch (const OptionValueError& e) {
        const std::string message = e.what();
        return usage_error(app, message.rfind(e.option(), 0) == 0
                                    ? CLI::ValidationError(message)
                                    : CLI::ValidationError(e.option(), message));
    } catch (const OutputConflict& e) {
        // Found from the command line and the file system alone, before any work: a usage error.
        std::fprintf(stderr, "%s\nRun with --help for more information.\n", e.what());
        return kExitUsage;
    } catch (const tirpol::Error& e) {
        std::fprintf(stderr, "tirpol: error: %s\n", e.what());
        return kExitError;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tirpol: unexpected error: %s\n", e.what());
        return kExitError;
    }
    return kExitOk;
}

}  // namespace tirpol::cli
