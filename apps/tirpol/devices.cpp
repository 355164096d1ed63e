// `tirpol devices [--json]`: the cameras that can be opened now (Aravis discovery, V4L2 capture
// devices) and the serial ports where a rotation stage may be (FTDI/CDC adapters).

#include "cli.h"
#include "common_options.h"
#include "tirpol/acquisition/camera.h"

namespace tirpol::cli {

namespace {
void register_devices(CLI::App& app) {
    auto json = std::make_shared<bool>(false);
    auto* cmd = app.add_subcommand(
        "devices", "List cameras (Aravis, V4L2) and serial ports for rotation stages");
    add_json_flag(cmd, *json);
    cmd->callback([json] {
        const acquisition::DeviceList devices = acquisition::list_devices();
        *json ? print_json(acquisition::device_list_json(devices))
              : print_text(acquisition::device_list_text(devices));
    });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(30, register_devices);

}  // namespace tirpol::cli
