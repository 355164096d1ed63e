#include "tirpol/acquisition/internal/fluke_blackbody.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "tirpol/acquisition/internal/fluke_scpi.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::acquisition {

namespace {

namespace fs = fluke_scpi;
using Clock = std::chrono::steady_clock;

std::string printable(const std::string& text) {
    std::string out;
    for (char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        out += (c >= 0x20 && c < 0x7f) ? std::string(1, ch) : fmt::format("\\x{:02x}", c);
    }
    return out;
}

class FlukeBlackbody final : public BlackbodyController {
public:
    FlukeBlackbody(std::unique_ptr<BytePort> port, std::string uri,
                   const FlukeBlackbodyOptions& options)
        : m_port(std::move(port)), m_options(options) {
        m_info.uri = std::move(uri);
        m_info.min_set_point_k = options.min_set_point_k;
        m_info.max_set_point_k = options.max_set_point_k;
    }

    Status initialise() {
        if (auto s = m_port->discard_input(); !s) return s;
        auto idn = query(fs::kIdentify);
        if (!idn) return idn.error();
        const auto id = fs::parse_identity(idn.value());
        if (!id) return bad_reply("*IDN?", idn.value(), "manufacturer,model,serial,firmware");
        m_info.vendor = id->manufacturer;
        m_info.model = id->model;
        m_info.serial = id->serial;
        m_info.firmware = id->firmware;
        if (auto s = send(fs::kClearStatus); !s) return s;
        if (auto s = send(fs::kUnitsCelsius); !s) return s;
        return check_error_queue("UNIT:TEMP C");
    }

    BlackbodyInfo info() const override { return m_info; }

    Status set_temperature_k(double set_point_k) override {
        if (!(set_point_k >= m_info.min_set_point_k && set_point_k <= m_info.max_set_point_k))
            return DeviceError{
                DeviceErrorCode::InvalidArgument,
                fmt::format(
                    "{}: set-point {:.3f} K ({:.3f} °C) is outside the {} range {:.2f}–{:.2f} K",
                    m_info.uri, set_point_k, set_point_k - kZeroCelsiusK, m_info.model,
                    m_info.min_set_point_k, m_info.max_set_point_k)};
        if (auto s = send(fs::set_point_command(set_point_k - kZeroCelsiusK)); !s) return s;
        if (auto s = check_error_queue("SOUR:SPO"); !s) return s;
        auto back = number(fs::kReadSetPoint, "SOUR:SPO?");
        if (!back) return back.error();
        // The command carries millikelvin: a read-back further off means the device holds another
        // set-point.
        if (std::abs(back.value() + kZeroCelsiusK - set_point_k) > 0.0015)
            return DeviceError{
                DeviceErrorCode::DeviceFault,
                fmt::format("{}: set-point {:.3f} °C sent, the controller holds {:.3f} °C",
                            m_info.uri, set_point_k - kZeroCelsiusK, back.value())};
        return ok_status();
    }

    Result<BlackbodyStatus> status() override {
        auto tripped = query(fs::kReadCutoutTripped);
        if (!tripped) return tripped.error();
        const auto trip = fs::parse_flag(tripped.value());
        if (!trip) return bad_reply("SOUR:PROT:TRIP?", tripped.value(), "0 or 1");
        BlackbodyStatus s;
        auto t = number(fs::kReadTemperature, "SOUR:SENS:DATA?");
        if (!t) return t.error();
        s.temperature_k = t.value() + kZeroCelsiusK;
        if (*trip)
            return DeviceError{DeviceErrorCode::DeviceFault,
                               fmt::format("{}: the over-temperature cutout has tripped, the "
                                           "heater is off (plate at {:.2f} K); reset the "
                                           "cutout at the controller",
                                           m_info.uri, s.temperature_k)};
        auto sp = number(fs::kReadSetPoint, "SOUR:SPO?");
        if (!sp) return sp.error();
        s.set_point_k = sp.value() + kZeroCelsiusK;
        auto stable = query(fs::kReadStability);
        if (!stable) return stable.error();
        const auto flag = fs::parse_flag(stable.value());
        if (!flag) return bad_reply("SOUR:STAB:TEST?", stable.value(), "0 or 1");
        s.stable = *flag;
        return s;
    }

private:
    DeviceError bad_reply(const char* command, const std::string& reply,
                          const char* expected) const {
        return {
            DeviceErrorCode::BadReply,
            fmt::format(
                "{}: reply \"{}\" to {} is not {} (garbled line? check the baud rate and cable)",
                m_info.uri, printable(reply), command, expected)};
    }

    Status send(std::string_view command) {
        const auto* p = reinterpret_cast<const std::uint8_t*>(command.data());
        return m_port->write({p, command.size()}, m_options.reply_timeout);
    }

    /// One reply line (without CR LF) to `command`, within the reply timeout.
    Result<std::string> query(std::string_view command) {
        if (auto s = send(command); !s) return s.error();
        const auto deadline = Clock::now() + m_options.reply_timeout;
        for (;;) {
            const auto lf = std::find(m_rx.begin(), m_rx.end(), '\n');
            if (lf != m_rx.end()) {
                std::string line(m_rx.begin(), lf);
                m_rx.erase(m_rx.begin(), lf + 1);
                if (!line.empty() && line.back() == '\r') line.pop_back();
                return line;
            }
            const auto left =
                std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
            auto bytes = m_port->read_some(std::max(left, std::chrono::milliseconds(0)));
            if (!bytes) {
                if (bytes.error().code != DeviceErrorCode::Timeout) return bytes.error();
                m_rx.clear();  // a late reply would answer the next query
                return DeviceError{DeviceErrorCode::Timeout,
                                   fmt::format("{}: no reply to {} within {} ms (controller off, "
                                               "wrong port or baud rate?)",
                                               m_info.uri, command.substr(0, command.size() - 1),
                                               m_options.reply_timeout.count())};
            }
            m_rx.insert(m_rx.end(), bytes.value().begin(), bytes.value().end());
        }
    }

    Result<double> number(std::string_view command, const char* name) {
        auto reply = query(command);
        if (!reply) return reply.error();
        const auto v = fs::parse_number(reply.value());
        if (!v) return bad_reply(name, reply.value(), "a number");
        return *v;
    }

    /// SYST:ERR? after a command without a reply: SCPI's only way to learn it was refused.
    Status check_error_queue(const char* after) {
        auto reply = query(fs::kReadError);
        if (!reply) return reply.error();
        const auto e = fs::parse_error(reply.value());
        if (!e) return bad_reply("SYST:ERR?", reply.value(), "<code>,\"<message>\"");
        if (e->code == 0) return ok_status();
        return DeviceError{
            e->code == -222 ? DeviceErrorCode::InvalidArgument : DeviceErrorCode::DeviceFault,
            fmt::format("{}: {} refused: error {} \"{}\"", m_info.uri, after, e->code, e->message)};
    }

    std::unique_ptr<BytePort> m_port;
    FlukeBlackbodyOptions m_options;
    BlackbodyInfo m_info;
    std::string m_rx;
};

}  // namespace

Result<std::unique_ptr<BlackbodyController>> open_fluke_blackbody(
    std::unique_ptr<BytePort> port, std::string uri, const FlukeBlackbodyOptions& options) {
    auto device = std::make_unique<FlukeBlackbody>(std::move(port), std::move(uri), options);
    if (auto s = device->initialise(); !s) return s.error();
    return std::unique_ptr<BlackbodyController>(std::move(device));
}

}  // namespace tirpol::acquisition
