#include <fmt/format.h>

#include "scheme_registry.h"
#include "tirpol/acquisition/camera.h"
#include "tirpol/acquisition/device_uri.h"
#ifdef TIRPOL_HAVE_ARAVIS
#include "tirpol/acquisition/internal/aravis_camera.h"
#endif
#include "tirpol/acquisition/sim/simulated_camera.h"
#ifdef TIRPOL_HAVE_V4L2
#include "tirpol/acquisition/internal/lepton_frame.h"
#include "tirpol/acquisition/internal/v4l2_camera.h"
#endif
#include "tirpol/core/error.h"

namespace tirpol::acquisition {

namespace {

[[maybe_unused]] std::optional<int> optional_int(const DeviceUri& u, const char* key) {
    if (u.query.count(key) == 0) return std::nullopt;
    return u.integer(key, 0);
}

[[maybe_unused]] std::optional<double> optional_number(const DeviceUri& u, const char* key) {
    if (u.query.count(key) == 0) return std::nullopt;
    return u.number(key, 0.0);
}

#ifdef TIRPOL_HAVE_ARAVIS
Result<std::unique_ptr<Camera>> open_aravis(const DeviceUri& u) {
    u.check_keys({"pixel_format", "width", "height", "fps", "trigger", "buffers", "packet_size",
                  "control_wait_s", "microgrid"});
    if (u.target.empty()) fail("device URI '{}': expected aravis://<device-id>", u.text);
    AravisCameraOptions options;
    if (u.query.count("pixel_format") != 0) options.pixel_format = u.query.at("pixel_format");
    if (u.query.count("microgrid") != 0)
        options.microgrid_pattern_deg = parse_microgrid_pattern_deg(
            u.query.at("microgrid"), fmt::format("device URI '{}': microgrid", u.text));
    options.width = optional_int(u, "width");
    options.height = optional_int(u, "height");
    options.frame_rate_hz = optional_number(u, "fps");
    options.stream_buffers = u.integer("buffers", options.stream_buffers);
    if (const auto wait_s = optional_number(u, "control_wait_s")) {
        if (!(*wait_s >= 0.0 && *wait_s <= 600.0))
            fail("device URI '{}': control_wait_s={} (expected 0 to 600 seconds)", u.text, *wait_s);
        options.control_wait =
            std::chrono::milliseconds(static_cast<std::int64_t>(*wait_s * 1000.0));
    }
    if (u.query.count("trigger") != 0) {
        const std::string& t = u.query.at("trigger");
        if (t != "software" && t != "off")
            fail("device URI '{}': trigger={} (expected software or off)", u.text, t);
        options.software_trigger = t == "software";
    }
    if (u.query.count("packet_size") != 0) {
        const std::string& p = u.query.at("packet_size");
        if (p != "auto" && p != "keep")
            fail("device URI '{}': packet_size={} (expected auto or keep)", u.text, p);
        options.auto_packet_size = p == "auto";
    }
    return open_aravis_camera(u.target, options);
}
#endif

#ifdef TIRPOL_HAVE_V4L2
Result<std::unique_ptr<Camera>> open_v4l2(const DeviceUri& u) {
    u.check_keys({"format", "width", "height", "fps", "buffers", "telemetry", "microgrid"});
    if (u.target.empty() || u.target.front() != '/')
        fail("device URI '{}': expected v4l2:///dev/videoN (an absolute device path)", u.text);
    V4l2CameraOptions options;
    if (u.query.count("format") != 0) options.pixel_format = u.query.at("format");
    options.width = optional_int(u, "width");
    options.height = optional_int(u, "height");
    options.frame_rate_hz = optional_number(u, "fps");
    const int buffers = u.integer("buffers", static_cast<int>(options.buffers));
    if (buffers < 2 || buffers > 64)
        fail("device URI '{}': buffers={} (expected 2…64)", u.text, buffers);
    options.buffers = static_cast<unsigned>(buffers);
    if (u.query.count("microgrid") != 0)
        options.microgrid_pattern_deg = parse_microgrid_pattern_deg(
            u.query.at("microgrid"), fmt::format("device URI '{}': microgrid", u.text));
    std::optional<LeptonTelemetryLocation> telemetry;
    if (u.query.count("telemetry") != 0) {
        const std::string& t = u.query.at("telemetry");
        if (t != "footer" && t != "header")
            fail(
                "device URI '{}': telemetry={} (expected footer or header: where the Lepton puts "
                "its telemetry rows)",
                u.text, t);
        telemetry =
            t == "footer" ? LeptonTelemetryLocation::Footer : LeptonTelemetryLocation::Header;
    }
    auto camera = open_v4l2_camera(u.target, options);
    if (!camera || !telemetry) return camera;
    return wrap_lepton_telemetry_camera(std::move(camera.value()), *telemetry);
}
#endif

/// The built-in schemes register through the same call as a plug-in, the first time the table is
/// used.
detail::SchemeRegistry<CameraFactory>& registry() {
    static detail::SchemeRegistry<CameraFactory> table;
    [[maybe_unused]] static const bool built_in = [] {
#ifdef TIRPOL_HAVE_ARAVIS
        table.register_scheme(
            "aravis", [](const std::string& uri) { return open_aravis(parse_device_uri(uri)); });
#endif
#ifdef TIRPOL_HAVE_V4L2
        table.register_scheme(
            "v4l2", [](const std::string& uri) { return open_v4l2(parse_device_uri(uri)); });
#endif
        table.register_scheme("sim", [](const std::string& uri) -> Result<std::unique_ptr<Camera>> {
            return std::unique_ptr<Camera>(open_simulated_camera(uri));
        });
        return true;
    }();
    return table;
}

}  // namespace

Result<std::unique_ptr<Camera>> open_camera(const std::string& uri) {
    const DeviceUri u = parse_device_uri(uri);
    const CameraFactory factory = registry().find(u.scheme);
    if (!factory) throw Error(registry().unknown_scheme_message("camera", u.scheme, uri));
    return factory(uri);
}

CameraFactory register_camera_scheme(const std::string& scheme, CameraFactory factory) {
    return registry().register_scheme(scheme, std::move(factory), "register_camera_scheme");
}

std::vector<std::string> camera_schemes() { return registry().schemes(); }

std::vector<CameraDescriptor> list_cameras() {
    std::vector<CameraDescriptor> cameras;
#ifdef TIRPOL_HAVE_ARAVIS
    for (const auto& d : discover_aravis_cameras()) {
        const std::string where =
            d.address.empty() ? d.protocol : fmt::format("{} at {}", d.protocol, d.address);
        cameras.push_back({"aravis://" + d.id, fmt::format("{} {} (serial {}), {}", d.vendor,
                                                           d.model, d.serial, where)});
    }
#endif
#ifdef TIRPOL_HAVE_V4L2
    for (const auto& d : discover_v4l2_cameras())
        cameras.push_back(
            {"v4l2://" + d.path, fmt::format("{} ({}, {})", d.card, d.driver, d.bus_info)});
#endif
    return cameras;
}

}  // namespace tirpol::acquisition
