#include "cli.h"

#include <cstdio>

#include "tirpol/core/error.h"
#include "tirpol/core/log.h"

namespace tirpol::cli {

int run(int argc, char** argv) {
    CLI::App app{"tirpol — thermal-infrared polarimetry with the instrument in the loop"};
    app.require_subcommand(1);
    std::string log_level = "info";
    app.add_option("--log-level", log_level, "trace, debug, info, warn, error or off")->capture_default_str();
    app.parse_complete_callback([&] { set_log_level(log_level); });

    register_info(app);
    register_planck(app);
    register_demo(app);

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
