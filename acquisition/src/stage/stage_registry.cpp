#include <fmt/format.h>

#include "device_uri_query.h"
#include "scheme_registry.h"
#include "tirpol/acquisition/device_uri.h"
#include "tirpol/acquisition/internal/apt_stage.h"
#include "tirpol/acquisition/internal/elliptec_stage.h"
#include "tirpol/acquisition/internal/ftdi_port.h"
#include "tirpol/acquisition/internal/serial_port.h"
#include "tirpol/acquisition/internal/sim_stage.h"
#include "tirpol/acquisition/stage.h"

namespace tirpol::acquisition {

namespace {

using detail::check_uri_keys;
using detail::uri_integer;
using detail::uri_number;
DeviceError bad(const std::string& uri, const std::string& what) {
    return detail::bad_uri(uri, what);
}

Result<std::unique_ptr<Stage>> open_apt(const std::string& uri, const DeviceUri& u, bool usb) {
    if (auto s = check_uri_keys(uri, u, {"counts_per_degree", "channel", "address", "timeout_ms"});
        !s)
        return s.error();
    AptStageOptions options;
    auto cpd = uri_number(uri, u, "counts_per_degree", options.counts_per_degree);
    auto channel = uri_integer(uri, u, "channel", options.channel);
    auto address = uri_integer(uri, u, "address", options.address);
    auto timeout =
        uri_integer(uri, u, "timeout_ms", static_cast<int>(options.reply_timeout.count()));
    if (!cpd) return cpd.error();
    if (!channel) return channel.error();
    if (!address) return address.error();
    if (!timeout) return timeout.error();
    if (channel.value() < 1 || channel.value() > 255 || address.value() < 0 ||
        address.value() > 0x7F)
        return bad(uri, "channel must be 1–255 and address 0–0x7F");
    options.counts_per_degree = cpd.value();
    options.channel = static_cast<std::uint8_t>(channel.value());
    options.address = static_cast<std::uint8_t>(address.value());
    options.reply_timeout = std::chrono::milliseconds(timeout.value());
    const SerialSettings settings{115200, true};
#ifdef TIRPOL_HAVE_LIBUSB
    auto port = usb ? open_ftdi_usb(u.target, settings) : open_serial_port(u.target, settings);
#else
    (void)usb;  // thorlabs-apt+usb is registered only when built with libusb
    auto port = open_serial_port(u.target, settings);
#endif
    if (!port) return port.error();
    return open_apt_stage(std::move(port.value()), uri, options);
}

Result<std::unique_ptr<Stage>> open_elliptec(const std::string& uri, const DeviceUri& u) {
    if (auto s = check_uri_keys(uri, u, {"address", "timeout_ms"}); !s) return s.error();
    ElliptecStageOptions options;
    auto it = u.query.find("address");
    if (it != u.query.end()) {
        if (it->second.size() != 1)
            return bad(uri, fmt::format("address={}: expected one hex digit 0–F", it->second));
        options.address =
            static_cast<char>(std::toupper(static_cast<unsigned char>(it->second[0])));
    }
    auto timeout =
        uri_integer(uri, u, "timeout_ms", static_cast<int>(options.reply_timeout.count()));
    if (!timeout) return timeout.error();
    options.reply_timeout = std::chrono::milliseconds(timeout.value());
    auto port = open_serial_port(u.target, SerialSettings{9600, false});
    if (!port) return port.error();
    return open_elliptec_stage(std::move(port.value()), uri, options);
}

Result<std::unique_ptr<Stage>> open_sim(const std::string& uri, const DeviceUri& u) {
    if (auto s = check_uri_keys(uri, u, {"deg_per_s", "start_deg", "fail_on_move"}); !s)
        return s.error();
    SimulatedStageOptions options;
    auto speed = uri_number(uri, u, "deg_per_s", 0.0);
    auto start = uri_number(uri, u, "start_deg", 0.0);
    auto fail = uri_integer(uri, u, "fail_on_move", 0);
    if (!speed) return speed.error();
    if (!start) return start.error();
    if (!fail) return fail.error();
    if (speed.value() < 0.0) return bad(uri, "deg_per_s must be ≥ 0");
    options.deg_per_s = speed.value();
    options.start_angle_deg = start.value();
    if (fail.value() > 0) options.fail_on_move = fail.value();
    return make_simulated_stage(uri, options);
}

/// Parses the URI and hands it to one of the built-in openers above.
template <typename Open>
StageFactory built_in(Open open) {
    return [open](const std::string& uri) -> Result<std::unique_ptr<Stage>> {
        auto parsed = split_device_uri(uri);
        if (!parsed) return parsed.error();
        return open(uri, parsed.value());
    };
}

/// The built-in schemes register through the same call as a plug-in, the first time the table is
/// used.
detail::SchemeRegistry<StageFactory>& registry() {
    static detail::SchemeRegistry<StageFactory> table;
    [[maybe_unused]] static const bool built_in_registered = [] {
        table.register_scheme("thorlabs-apt",
                              built_in([](const std::string& uri, const DeviceUri& u) {
                                  return open_apt(uri, u, false);
                              }));
#ifdef TIRPOL_HAVE_LIBUSB
        table.register_scheme("thorlabs-apt+usb",
                              built_in([](const std::string& uri, const DeviceUri& u) {
                                  return open_apt(uri, u, true);
                              }));
#endif
        table.register_scheme("elliptec", built_in(open_elliptec));
        table.register_scheme("sim", built_in(open_sim));
        return true;
    }();
    return table;
}

}  // namespace

Result<std::unique_ptr<Stage>> open_stage(const std::string& uri) {
    auto parsed = split_device_uri(uri);
    if (!parsed) return parsed.error();
    const StageFactory factory = registry().find(parsed.value().scheme);
    if (!factory)
        return DeviceError{DeviceErrorCode::InvalidArgument,
                           registry().unknown_scheme_message("stage", parsed.value().scheme, uri)};
    return factory(uri);
}

StageFactory register_stage_scheme(const std::string& scheme, StageFactory factory) {
    return registry().register_scheme(scheme, std::move(factory), "register_stage_scheme");
}

std::vector<std::string> stage_schemes() { return registry().schemes(); }

}  // namespace tirpol::acquisition
