// `tirpol info FILE.exr`: size, channels, header attributes and per-channel statistics.
// `tirpol info SESSION`: a capture session's summary (records, audit, FFCs, lost-step checks).

#include "cli.h"
#include "common_options.h"
#include "tirpol/core/path_info.h"

namespace tirpol::cli {

namespace {
void register_info(CLI::App& app) {
    auto path = std::make_shared<std::string>();
    auto json = std::make_shared<bool>(false);
    auto* cmd =
        app.add_subcommand("info",
                           "Describe an EXR image (size, channels, header, statistics) or a "
                           "capture session directory (records, audit, FFCs, lost-step checks)");
    cmd->add_option("FILE", *path, "OpenEXR file or session directory")->required();
    add_json_flag(cmd, *json);
    cmd->callback([path, json] {
        const PathInfo info = describe_path(*path);
        *json ? print_json(path_info_json(info)) : print_text(path_info_text(info));
    });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(10, register_info);

}  // namespace tirpol::cli
