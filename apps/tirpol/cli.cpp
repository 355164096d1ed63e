#include "cli.h"

#include <algorithm>
#include <cstdio>

#include "tirpol/core/error.h"
#include "tirpol/core/log.h"

namespace tirpol::cli {

namespace {
std::vector<std::pair<int, CommandRegistration>>& registry() {
    static std::vector<std::pair<int, CommandRegistration>> r;
    return r;
}
}  // namespace

bool register_command(int order, CommandRegistration registration) {
    registry().emplace_back(order, std::move(registration));
    return true;
}

int run(int argc, char** argv) {
    CLI::App app{"tirpol — thermal-infrared polarimetry with the instrument in the loop"};
    app.require_subcommand(1);
    std::string log_level = "info";
    app.add_option("--log-level", log_level, "trace, debug, info, warn, error or off")->capture_default_str();
    app.parse_complete_callback([&] { set_log_level(log_level); });

    auto& commands = registry();
    std::stable_sort(commands.begin(), commands.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [order, add] : commands) add(app);

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e);
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
