// `tirpol devices [--json]`: the cameras that can be opened now (Aravis discovery, V4L2 capture
// devices) and the serial ports where a rotation stage may be (FTDI/CDC adapters).

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli.h"
#include "tirpol/acquisition/camera.h"
#include "tirpol/core/utf8.h"

namespace tirpol::cli {

namespace {

struct SerialPort {
    std::string path;    ///< the stable name when there is one (/dev/serial/by-id/…)
    std::string device;  ///< the kernel node it points to (/dev/ttyUSB0)
};

/// /dev/serial/by-id/* first (names carry vendor and serial, stable across re-plugging), then the
/// /dev/ttyUSB* (FTDI, as in Thorlabs K-Cube/T-Cube and Elliptec bus boards) and /dev/ttyACM* nodes
/// that no by-id link already names.
std::vector<SerialPort> serial_port_candidates() {
    namespace fs = std::filesystem;
    std::vector<SerialPort> ports;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator("/dev/serial/by-id", ec)) {
        const fs::path target = fs::weakly_canonical(entry.path(), ec);
        ports.push_back({entry.path().string(), ec ? std::string() : target.string()});
    }
    std::vector<std::string> nodes;
    for (const auto& entry : fs::directory_iterator("/dev", ec)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("ttyUSB", 0) == 0 || name.rfind("ttyACM", 0) == 0)
            nodes.push_back(entry.path().string());
    }
    std::sort(nodes.begin(), nodes.end());
    std::sort(ports.begin(), ports.end(),
              [](const SerialPort& a, const SerialPort& b) { return a.path < b.path; });
    for (const auto& node : nodes) {
        const bool named = std::any_of(ports.begin(), ports.end(),
                                       [&](const SerialPort& p) { return p.device == node; });
        if (!named) ports.push_back({node, node});
    }
    return ports;
}

void run_devices(bool json) {
    const auto cameras = acquisition::list_cameras();
    const auto ports = serial_port_candidates();
    if (json) {
        nlohmann::json out;
        out["cameras"] = nlohmann::json::array();
        for (const auto& c : cameras)
            out["cameras"].push_back({{"uri", c.uri}, {"description", c.description}});
        out["serial_ports"] = nlohmann::json::array();
        for (const auto& p : ports)
            out["serial_ports"].push_back({{"path", p.path}, {"device", p.device}});
        std::printf("%s\n", json_text(out, 2).c_str());
        return;
    }
    std::printf("cameras:\n");
    if (cameras.empty())
        std::printf(
            "  (none found: no GigE Vision/USB3 Vision camera answered, no V4L2 capture device)\n");
    for (const auto& c : cameras) std::printf("  %-40s %s\n", c.uri.c_str(), c.description.c_str());
    std::printf("serial ports (stages: thorlabs-apt://PORT, elliptec://PORT):\n");
    if (ports.empty())
        std::printf("  (none found under /dev/serial/by-id, /dev/ttyUSB*, /dev/ttyACM*)\n");
    for (const auto& p : ports) {
        if (p.path == p.device)
            std::printf("  %s\n", p.path.c_str());
        else
            std::printf("  %s -> %s\n", p.path.c_str(), p.device.c_str());
    }
}

void register_devices(CLI::App& app) {
    auto json = std::make_shared<bool>(false);
    auto* cmd = app.add_subcommand(
        "devices", "List cameras (Aravis, V4L2) and serial ports for rotation stages");
    cmd->add_flag("--json", *json, "Print JSON");
    cmd->callback([json] { run_devices(*json); });
}

}  // namespace

TIRPOL_REGISTER_COMMAND(30, register_devices);

}  // namespace tirpol::cli
