#include <fmt/format.h>

#include <thread>

#include "device_uri_query.h"
#include "tirpol/acquisition/blackbody.h"
#include "tirpol/acquisition/internal/blackbody_simulator.h"
#include "tirpol/acquisition/internal/fluke_blackbody.h"
#include "tirpol/acquisition/internal/serial_port.h"
#include "tirpol/core/error.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::acquisition {

namespace {

using detail::bad_uri;

/// The simulator in-process behind a BytePort: the driver speaks the same bytes as on a serial
/// line.
class SimulatorPort final : public BytePort {
public:
    explicit SimulatorPort(BlackbodySimulatorOptions options) : m_simulator(std::move(options)) {}
    Status write(std::span<const std::uint8_t> bytes, std::chrono::milliseconds) override {
        const auto reply = m_simulator.receive(bytes, PtyDevice::Clock::now());
        m_pending.insert(m_pending.end(), reply.begin(), reply.end());
        return ok_status();
    }
    Result<std::vector<std::uint8_t>> read_some(std::chrono::milliseconds timeout) override {
        if (m_pending.empty()) {
            std::this_thread::sleep_for(
                timeout);  // a silent device: the host waits out its timeout
            return DeviceError{DeviceErrorCode::Timeout,
                               fmt::format("{}: no reply within {} ms", name(), timeout.count())};
        }
        return std::exchange(m_pending, {});
    }
    Status discard_input() override {
        m_pending.clear();
        return ok_status();
    }
    std::string name() const override { return "sim://"; }

private:
    BlackbodySimulator m_simulator;
    std::vector<std::uint8_t> m_pending;
};

FlukeBlackbodyOptions model_range(const std::string& model) {
    FlukeBlackbodyOptions o;
    const bool is_4181 = model == "4181";
    o.min_set_point_k =
        (is_4181 ? fluke_scpi::kModel4181MinC : fluke_scpi::kModel4180MinC) + kZeroCelsiusK;
    o.max_set_point_k =
        (is_4181 ? fluke_scpi::kModel4181MaxC : fluke_scpi::kModel4180MaxC) + kZeroCelsiusK;
    return o;
}

Result<std::unique_ptr<BlackbodyController>> open_serial_fluke(const std::string& uri,
                                                               const DeviceUri& u,
                                                               const std::string& model) {
    if (auto s = detail::check_uri_keys(uri, u, {"baud", "timeout_ms"}); !s) return s.error();
    auto baud = detail::uri_integer(uri, u, "baud", fluke_scpi::kDefaultBaud);
    auto timeout = detail::uri_integer(uri, u, "timeout_ms", 1000);
    if (!baud) return baud.error();
    if (!timeout) return timeout.error();
    if (timeout.value() < 1) return bad_uri(uri, "timeout_ms must be ≥ 1");
    if (u.target.empty())
        return bad_uri(uri, "expected a serial device path, e.g. fluke-4180:///dev/ttyUSB0");
    FlukeBlackbodyOptions options = model_range(model);
    options.reply_timeout = std::chrono::milliseconds(timeout.value());
    auto port = open_serial_port(u.target, SerialSettings{baud.value(), false});
    if (!port) return port.error();
    return open_fluke_blackbody(std::move(port.value()), uri, options);
}

Result<std::unique_ptr<BlackbodyController>> open_sim(const std::string& uri, const DeviceUri& u) {
    if (auto s = detail::check_uri_keys(uri, u,
                                        {"tau_s", "ambient_k", "noise_k", "limit_k", "window_s",
                                         "model", "fault", "fault_on_set", "seed"});
        !s)
        return s.error();
    BlackbodySimulatorOptions o;
    auto tau = detail::uri_number(uri, u, "tau_s", o.time_constant_s);
    auto ambient = detail::uri_number(uri, u, "ambient_k", o.ambient_k);
    auto noise = detail::uri_number(uri, u, "noise_k", o.noise_k);
    auto limit = detail::uri_number(uri, u, "limit_k", o.stability_limit_k);
    auto window = detail::uri_number(uri, u, "window_s", o.stability_window_s);
    auto fault_on = detail::uri_integer(uri, u, "fault_on_set", o.fault_on_set);
    auto seed = detail::uri_integer(uri, u, "seed", 1);
    for (const auto* r : {&tau, &ambient, &noise, &limit, &window})
        if (!*r) return r->error();
    if (!fault_on) return fault_on.error();
    if (!seed) return seed.error();
    o.time_constant_s = tau.value();
    o.ambient_k = ambient.value();
    o.noise_k = noise.value();
    o.stability_limit_k = limit.value();
    o.stability_window_s = window.value();
    o.fault_on_set = fault_on.value();
    o.seed = static_cast<std::uint64_t>(seed.value());
    if (auto it = u.query.find("model"); it != u.query.end()) o.model = it->second;
    if (auto it = u.query.find("fault"); it != u.query.end()) {
        const auto f = parse_blackbody_fault(it->second);
        if (!f)
            return bad_uri(
                uri, fmt::format("fault={}: expected none, over-temperature, no-reply or garbled",
                                 it->second));
        o.fault = *f;
    }
    const std::string model = o.model;
    std::unique_ptr<BytePort> port;
    try {
        port = std::make_unique<SimulatorPort>(std::move(o));
    } catch (const Error& e) {
        return bad_uri(uri, e.what());
    }
    FlukeBlackbodyOptions options = model_range(model);
    options.reply_timeout = std::chrono::milliseconds(200);
    return open_fluke_blackbody(std::move(port), uri, options);
}

}  // namespace

Result<std::unique_ptr<BlackbodyController>> open_blackbody(const std::string& uri) {
    auto parsed = split_device_uri(uri);
    if (!parsed) return parsed.error();
    const DeviceUri& u = parsed.value();
    if (u.scheme == "fluke-4180") return open_serial_fluke(uri, u, "4180");
    if (u.scheme == "fluke-4181") return open_serial_fluke(uri, u, "4181");
    if (u.scheme == "sim") return open_sim(uri, u);
    return bad_uri(
        uri, fmt::format(
                 "unknown blackbody controller type '{}' (expected fluke-4180, fluke-4181 or sim)",
                 u.scheme));
}

}  // namespace tirpol::acquisition
