#include "tirpol/acquisition/internal/elliptec_stage.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <cmath>
#include <mutex>
#include <thread>

#include "move_preconditions.h"
#include "tirpol/acquisition/internal/angles.h"
#include "tirpol/acquisition/internal/elliptec_protocol.h"

namespace tirpol::acquisition {

namespace {

using Clock = std::chrono::steady_clock;
namespace ell = elliptec;

class ElliptecStage final : public Stage {
public:
    ElliptecStage(std::unique_ptr<BytePort> port, std::string uri, ElliptecStageOptions options)
        : m_port(std::move(port)), m_options(options) {
        m_info.uri = std::move(uri);
        m_info.vendor = "Thorlabs";
    }

    Status initialise() {
        if (auto s = m_port->discard_input(); !s) return s;
        auto reply = transact(ell::info_request(m_options.address),
                              Clock::now() + m_options.reply_timeout, "IN");
        if (!reply) return reply.error();
        const auto info = ell::parse_info(reply.value());
        if (!info)
            return DeviceError{
                DeviceErrorCode::BadReply,
                fmt::format(
                    "{}: malformed IN reply \"{}\" (expected 30 characters of fields after IN)",
                    m_info.uri, reply.value().data)};
        if (info->travel != 360 || info->pulses == 0)
            return DeviceError{
                DeviceErrorCode::NotSupported,
                fmt::format("{}: ELL{} reports a travel of {} units with {} pulses; only rotary "
                            "mounts (travel 360°) drive a polarizer",
                            m_info.uri, info->motor_type, info->travel, info->pulses)};
        m_info.model = fmt::format("ELL{}", info->motor_type);
        m_info.serial = info->serial;
        m_info.firmware = std::to_string(info->firmware);
        m_info.counts_per_degree = info->pulses_per_unit();
        return ok_status();
    }

    StageInfo info() const override { return m_info; }
    bool is_homed() const override { return m_homed; }

    Status home(std::chrono::milliseconds timeout) override {
        const MotionScope motion(*this);
        auto reply = transact(ell::home(m_options.address, true), Clock::now() + timeout, "PO",
                              Motion::Stoppable);
        if (!reply) return reply.error();
        m_homed = true;
        return ok_status();
    }

    Status move_absolute(double angle_deg, std::chrono::milliseconds timeout) override {
        if (auto s = detail::check_absolute_move(m_info.uri, m_homed, angle_deg); !s) return s;
        const auto pulses = static_cast<std::int32_t>(
            std::llround(wrap_degrees(angle_deg) * m_info.counts_per_degree));
        const MotionScope motion(*this);
        auto reply = transact(ell::move_absolute(m_options.address, pulses), Clock::now() + timeout,
                              "PO", Motion::Stoppable);
        if (!reply) return reply.error();
        return ok_status();
    }

    Result<double> position_deg() override {
        auto reply = transact(ell::get_position(m_options.address),
                              Clock::now() + m_options.reply_timeout, "PO");
        if (!reply) return reply.error();
        const auto pulses = ell::decode_position(reply.value().data);
        if (!pulses)
            return DeviceError{DeviceErrorCode::BadReply,
                               fmt::format("{}: malformed PO reply \"{}\" (expected 8 hex digits)",
                                           m_info.uri, reply.value().data)};
        return wrap_degrees(*pulses / m_info.counts_per_degree);
    }

    Status stop() override {
        // Idle: nothing to stop, and its GS reply would only come in the way of the next command.
        if (!m_in_motion) return ok_status();
        m_stop_requested = true;
        return write(ell::stop(m_options.address));
    }

private:
    /// Marks a homing or move in progress (what stop() may stop); clears an earlier stop request.
    struct MotionScope {
        explicit MotionScope(ElliptecStage& stage) : m_stage(stage) {
            m_stage.m_stop_requested = false;
            m_stage.m_in_motion = true;
        }
        ~MotionScope() { m_stage.m_in_motion = false; }
        MotionScope(const MotionScope&) = delete;
        MotionScope& operator=(const MotionScope&) = delete;
        ElliptecStage& m_stage;
    };

    /// Whether stop() ends the wait (home, moves) or not (requests answered at once).
    enum class Motion { Stoppable, Immediate };

    /// Serialised: stop() writes from another thread while a move's thread may resend its command.
    Status write(const std::string& command) {
        const std::vector<std::uint8_t> bytes(command.begin(), command.end());
        const std::lock_guard lock(m_write_mutex);
        return m_port->write(bytes, m_options.reply_timeout);
    }

    /// Ends a motion cut short by stop(): reads up to the module's GS reply to `st`, so no reply of
    /// the interrupted motion is left to be taken for the answer to the next command.
    DeviceError stopped(const std::string& command) {
        const auto deadline = Clock::now() + m_options.reply_timeout;
        for (;;) {
            auto reply = read_reply(deadline, "st", false);
            if (!reply || reply.value().code == "GS") break;
        }
        return stop_error(command);
    }
    DeviceError stop_error(const std::string& command) const {
        return {DeviceErrorCode::Stopped,
                fmt::format("{}: '{}' ended by a stop request ('st' sent)", m_info.uri, command)};
    }

    /// Sends `command` and waits for the reply `expected` from our address. A GS reply with a
    /// non-zero status is a fault, except Busy, which is waited out (re-sending) until the
    /// deadline.
    Result<ell::Reply> transact(const std::string& command, Clock::time_point deadline,
                                const char* expected, Motion motion = Motion::Immediate) {
        bool busy_seen = false;
        const bool stoppable = motion == Motion::Stoppable;
        for (;;) {
            if (stoppable && m_stop_requested) return stopped(command);
            if (auto s = write(command); !s) return s.error();
            auto reply = read_reply(deadline, command, stoppable);
            if (stoppable && m_stop_requested && reply)  // a GS here is the module's answer to `st`
                return reply.value().code == "GS" ? stop_error(command) : stopped(command);
            if (!reply) {
                DeviceError e = reply.error();
                if (busy_seen && e.code == DeviceErrorCode::Timeout)
                    e.message += " (the module kept answering GS09 Busy)";
                return e;
            }
            const ell::Reply& r = reply.value();
            if (r.code == expected) return reply;
            if (r.code == "GS") {
                const auto status = ell::parse_status(r);
                if (!status)
                    return DeviceError{
                        DeviceErrorCode::BadReply,
                        fmt::format("{}: malformed GS reply \"{}\"", m_info.uri, r.data)};
                if (*status == ell::kOk)
                    continue;  // acknowledged without the data reply: ask again
                if (*status == ell::kBusy) {
                    busy_seen = true;
                    if (Clock::now() + std::chrono::milliseconds(50) >= deadline)
                        return DeviceError{
                            DeviceErrorCode::Timeout,
                            fmt::format("{}: '{}': the module stayed Busy (GS09) until the timeout",
                                        m_info.uri, command)};
                    std::this_thread::sleep_for(std::chrono::milliseconds(50));
                    continue;
                }
                return DeviceError{DeviceErrorCode::DeviceFault,
                                   fmt::format("{}: '{}' failed: status {:02X}: {}", m_info.uri,
                                               command, *status, ell::status_meaning(*status))};
            }
            return DeviceError{DeviceErrorCode::BadReply,
                               fmt::format("{}: '{}': expected a {} reply, got \"{}{}\"",
                                           m_info.uri, command, expected, r.code, r.data)};
        }
    }

    Result<ell::Reply> read_reply(Clock::time_point deadline, const std::string& command,
                                  bool stoppable) {
        for (;;) {
            while (auto line = ell::take_line(m_rx)) {
                const auto reply = ell::parse_reply(*line);
                if (!reply) {
                    spdlog::debug("{}: ignoring unparseable line \"{}\"", m_info.uri, *line);
                    continue;
                }
                if (reply->address != m_options.address) continue;  // another module on the bus
                return *reply;
            }
            if (stoppable && m_stop_requested) return stopped(command);
            const auto left =
                std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
            if (left.count() <= 0)
                return DeviceError{
                    DeviceErrorCode::Timeout,
                    fmt::format("{}: no reply to '{}' in time", m_info.uri, command)};
            // Short reads while a motion runs, so a stop() from another thread is noticed promptly.
            auto bytes =
                m_port->read_some(stoppable ? std::min(left, std::chrono::milliseconds(50)) : left);
            if (!bytes && bytes.error().code == DeviceErrorCode::Timeout && Clock::now() < deadline)
                continue;
            if (!bytes) {
                DeviceError e = bytes.error();
                e.message = e.code == DeviceErrorCode::Timeout
                                ? fmt::format("{}: no reply to '{}' in time", m_info.uri, command)
                                : fmt::format("{}: '{}': {}", m_info.uri, command, e.message);
                return e;
            }
            m_rx.append(bytes.value().begin(), bytes.value().end());
        }
    }

    std::unique_ptr<BytePort> m_port;
    ElliptecStageOptions m_options;
    StageInfo m_info;
    bool m_homed = false;
    std::string m_rx;
    std::mutex m_write_mutex;
    std::atomic<bool> m_in_motion{false};
    std::atomic<bool> m_stop_requested{false};
};

}  // namespace

Result<std::unique_ptr<Stage>> open_elliptec_stage(std::unique_ptr<BytePort> port, std::string uri,
                                                   const ElliptecStageOptions& options) {
    if (!ell::valid_address(options.address))
        return DeviceError{DeviceErrorCode::InvalidArgument,
                           fmt::format("{}: address '{}' is not 0–9 or A–F", uri, options.address)};
    auto stage = std::make_unique<ElliptecStage>(std::move(port), std::move(uri), options);
    if (auto s = stage->initialise(); !s) return s.error();
    return std::unique_ptr<Stage>(std::move(stage));
}

}  // namespace tirpol::acquisition
