#include <fmt/printf.h>

#include <algorithm>

#include "tirpol/acquisition/camera.h"

namespace tirpol::acquisition {

std::vector<SerialPort> list_serial_ports(const std::filesystem::path& dev) {
    namespace fs = std::filesystem;
    std::vector<SerialPort> ports;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dev / "serial/by-id", ec)) {
        const fs::path target = fs::weakly_canonical(entry.path(), ec);
        ports.push_back({entry.path().string(), ec ? std::string() : target.string()});
    }
    std::vector<std::string> nodes;
    for (const auto& entry : fs::directory_iterator(dev, ec)) {
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

DeviceList list_devices() { return {list_cameras(), list_serial_ports()}; }

nlohmann::json device_list_json(const DeviceList& devices) {
    nlohmann::json out;
    out["cameras"] = nlohmann::json::array();
    for (const auto& c : devices.cameras)
        out["cameras"].push_back({{"uri", c.uri}, {"description", c.description}});
    out["serial_ports"] = nlohmann::json::array();
    for (const auto& p : devices.serial_ports)
        out["serial_ports"].push_back({{"path", p.path}, {"device", p.device}});
    return out;
}

std::string device_list_text(const DeviceList& devices) {
    std::string text = "cameras:\n";
    if (devices.cameras.empty())
        text +=
            "  (none found: no GigE Vision/USB3 Vision camera answered, no V4L2 capture device)\n";
    for (const auto& c : devices.cameras)
        text += fmt::sprintf("  %-40s %s\n", c.uri, c.description);
    text += "serial ports (stages: thorlabs-apt://PORT, elliptec://PORT):\n";
    if (devices.serial_ports.empty())
        text += "  (none found under /dev/serial/by-id, /dev/ttyUSB*, /dev/ttyACM*)\n";
    for (const auto& p : devices.serial_ports)
        text += p.path == p.device ? fmt::sprintf("  %s\n", p.path)
                                   : fmt::sprintf("  %s -> %s\n", p.path, p.device);
    return text;
}

}  // namespace tirpol::acquisition
