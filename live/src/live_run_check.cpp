#include <filesystem>

#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/live/live_server.h"

namespace tirpol::live {

void check_live_run(const LiveViewOptions& view, const ServerOptions& server) {
    try {
        validate(view);
        validate(server);
    } catch (const OptionValueError&) {
        throw;
    } catch (const Error& e) {
        // Every message of validate begins with what it is about: "--settle-s: …".
        const std::string message = e.what();
        throw OptionValueError(message.substr(0, message.find(':')), message);
    }
    if (view.snapshot_dir.empty()) return;
    OutputGuard()
        .input(view.calibration_path, "--calibration")
        .input(view.default_plan, "--plan")
        .output_folder(view.snapshot_dir, "--snapshot-dir", {"snapshot-*"})
        .check(view.force_snapshots);
    std::filesystem::create_directories(view.snapshot_dir);
}

}  // namespace tirpol::live
