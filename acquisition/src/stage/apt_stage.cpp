#include "tirpol/acquisition/internal/apt_stage.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>

#include "move_preconditions.h"
#include "tirpol/acquisition/internal/angles.h"

namespace tirpol::acquisition {

namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;
constexpr std::chrono::milliseconds kStopPoll{50};

class AptStage final : public Stage {
public:
    AptStage(std::unique_ptr<BytePort> port, std::string uri, AptStageOptions options)
        : m_port(std::move(port)), m_options(options) {
        m_info.uri = std::move(uri);
        m_info.vendor = "Thorlabs";
        m_info.counts_per_degree = options.counts_per_degree;
    }

    Status initialise() {
        if (auto s = send(apt::hw_no_flash_programming()); !s) return s;
        if (auto s = m_port->discard_input(); !s) return s;
        if (auto s = send(apt::hw_req_info()); !s) return s;
        auto reply =
            await({apt::kHwGetInfo}, Clock::now() + m_options.reply_timeout, "MGMSG_HW_GET_INFO");
        if (!reply) return reply.error();
        const auto info = apt::parse_hw_info(reply.value());
        if (!info) return bad_reply("MGMSG_HW_GET_INFO with an 84-byte data packet", reply.value());
        m_info.model = info->model;
        m_info.serial = std::to_string(info->serial);
        m_info.firmware = fmt::format("{}.{}.{}", info->firmware_major, info->firmware_interim,
                                      info->firmware_minor);
        if (auto s = send(apt::mod_set_chan_enable_state(m_options.channel, true)); !s) return s;
        auto status = request_status(Clock::now() + m_options.reply_timeout);
        if (!status) return status.error();
        m_homed = (status.value().status_bits & apt::kHomed) != 0;
        return ok_status();
    }

    StageInfo info() const override { return m_info; }
    bool is_homed() const override { return m_homed; }

    Status home(std::chrono::milliseconds timeout) override {
        const MotionScope motion(*this);
        if (auto s = send(apt::mot_move_home(m_options.channel)); !s) return s;
        auto reply = await({apt::kMotMoveHomed, apt::kMotMoveStopped}, Clock::now() + timeout,
                           "MGMSG_MOT_MOVE_HOMED");
        if (!reply) return with_motion_state(reply.error());
        if (reply.value().id == apt::kMotMoveStopped)
            return DeviceError{
                m_stop_requested ? DeviceErrorCode::Stopped : DeviceErrorCode::DeviceFault,
                fmt::format(
                    "{}: homing stopped before the home switch{}", m_info.uri,
                    m_stop_requested ? " (MGMSG_MOT_MOVE_STOP sent); the stage is not homed" : "")};
        m_homed = true;
        return ok_status();
    }

    Status move_absolute(double angle_deg, std::chrono::milliseconds timeout) override {
        if (auto s = detail::check_absolute_move(m_info.uri, m_homed, angle_deg); !s) return s;
        const auto target = static_cast<std::int32_t>(
            std::llround(wrap_degrees(angle_deg) * m_options.counts_per_degree));
        const MotionScope motion(*this);
        if (auto s = send(apt::mot_move_absolute(target, m_options.channel)); !s) return s;
        auto reply = await({apt::kMotMoveCompleted, apt::kMotMoveStopped}, Clock::now() + timeout,
                           "MGMSG_MOT_MOVE_COMPLETED");
        if (!reply) return with_motion_state(reply.error());
        const auto status = apt::parse_status_update(reply.value());
        if (!status) return bad_reply("a 14-byte status packet", reply.value());
        if (reply.value().id == apt::kMotMoveStopped && m_stop_requested)
            return DeviceError{
                DeviceErrorCode::Stopped,
                fmt::format("{}: move to {:.3f}° stopped at {:.3f}° (MGMSG_MOT_MOVE_STOP sent)",
                            m_info.uri, wrap_degrees(angle_deg),
                            status->position / m_options.counts_per_degree)};
        if (reply.value().id == apt::kMotMoveStopped || (status->status_bits & apt::kMotionError))
            return DeviceError{
                DeviceErrorCode::DeviceFault,
                fmt::format("{}: move to {:.3f}° stopped at {:.3f}° (status bits 0x{:08X}{})",
                            m_info.uri, wrap_degrees(angle_deg),
                            status->position / m_options.counts_per_degree, status->status_bits,
                            (status->status_bits & apt::kMotionError) ? ", motion error" : "")};
        return ok_status();
    }

    Result<double> position_deg() override {
        auto status = request_status(Clock::now() + m_options.reply_timeout);
        if (!status) return status.error();
        return wrap_degrees(status.value().position / m_options.counts_per_degree);
    }

    /// The K10CR1 reports its home sensor as the reverse hardware-limit bit of the status word.
    Result<bool> home_sensor_active() override {
        auto status = request_status(Clock::now() + m_options.reply_timeout);
        if (!status) return status.error();
        return (status.value().status_bits & apt::kCcwHardLimit) != 0;
    }

    /// Profiled stop: a stepper stopped abruptly can lose steps, and the position must stay true.
    Status stop() override {
        // Idle: nothing to stop, and a MOVE_STOPPED reply would later be taken for the next move's
        // end.
        if (!m_in_motion) return ok_status();
        m_stop_requested_at = Clock::now().time_since_epoch().count();
        m_stop_requested = true;
        return send(apt::mot_move_stop(m_options.channel, apt::StopMode::Profiled));
    }

private:
    /// Marks a homing or move in progress (what stop() may stop); clears an earlier stop request.
    struct MotionScope {
        explicit MotionScope(AptStage& stage) : m_stage(stage) {
            m_stage.m_stop_requested = false;
            m_stage.m_in_motion = true;
        }
        ~MotionScope() { m_stage.m_in_motion = false; }
        MotionScope(const MotionScope&) = delete;
        MotionScope& operator=(const MotionScope&) = delete;
        AptStage& m_stage;
    };

    /// Serialised: stop() writes from another thread while a move's thread may write a request.
    Status send(const std::vector<std::uint8_t>& bytes) {
        const std::lock_guard lock(m_write_mutex);
        return m_port->write(bytes, m_options.reply_timeout);
    }

    Result<apt::StatusUpdate> request_status(Clock::time_point deadline) {
        if (auto s = send(apt::mot_req_ustatus_update(m_options.channel)); !s) return s.error();
        auto reply = await({apt::kMotGetUStatusUpdate}, deadline, "MGMSG_MOT_GET_USTATUSUPDATE");
        if (!reply) return reply.error();
        const auto status = apt::parse_status_update(reply.value());
        if (!status) return bad_reply("a 14-byte status packet", reply.value());
        return *status;
    }

    /// After a timeout, says whether the stage is still moving (busy) or silent.
    DeviceError with_motion_state(DeviceError error) {
        if (error.code != DeviceErrorCode::Timeout) return error;
        auto status = request_status(Clock::now() + m_options.reply_timeout);
        if (status && (status.value().status_bits & apt::kMovingMask))
            error.message += fmt::format("; the stage is still moving (status bits 0x{:08X})",
                                         status.value().status_bits);
        else if (!status && status.error().code == DeviceErrorCode::Timeout)
            error.message += "; the controller does not answer status requests either";
        return error;
    }

    DeviceError bad_reply(const char* expected, const apt::Message& m) const {
        return {DeviceErrorCode::BadReply,
                fmt::format("{}: expected {}, got {} with {} data bytes", m_info.uri, expected,
                            apt::message_name(m.id), m.data.size())};
    }

    /// Reads messages until one with an id in `ids` arrives. Unsolicited status messages are
    /// skipped; an error report from the controller ends the wait.
    Result<apt::Message> await(std::initializer_list<std::uint16_t> ids, Clock::time_point deadline,
                               const char* what) {
        for (;;) {
            const auto decoded = apt::decode(m_rx);
            if (decoded.status == apt::DecodeStatus::Invalid) {
                spdlog::debug("{}: {}; resynchronising", m_info.uri, decoded.error);
                m_rx.erase(m_rx.begin(),
                           m_rx.begin() + static_cast<std::ptrdiff_t>(decoded.consumed));
                continue;
            }
            if (decoded.status == apt::DecodeStatus::Complete &&
                decoded.message.dest != apt::kHostAddress) {
                // Every controller message is addressed to the host; anything else is a misaligned
                // stream (line noise): drop one byte and look for the next header.
                spdlog::debug("{}: header addressed to 0x{:02X}, not the host; resynchronising",
                              m_info.uri, decoded.message.dest);
                m_rx.erase(m_rx.begin());
                continue;
            }
            if (decoded.status == apt::DecodeStatus::Complete) {
                m_rx.erase(m_rx.begin(),
                           m_rx.begin() + static_cast<std::ptrdiff_t>(decoded.consumed));
                const apt::Message& m = decoded.message;
                if (m.id == apt::kHwRichResponse) {
                    const auto r = apt::parse_rich_response(m);
                    return DeviceError{
                        DeviceErrorCode::DeviceFault,
                        r ? fmt::format("{}: controller error {} on {}: {}", m_info.uri, r->code,
                                        apt::message_name(r->message_id), r->text)
                          : fmt::format("{}: controller reported an error (malformed "
                                        "MGMSG_HW_RICHRESPONSE)",
                                        m_info.uri)};
                }
                if (m.id == apt::kHwResponse)
                    return DeviceError{
                        DeviceErrorCode::DeviceFault,
                        fmt::format("{}: controller reported an error (MGMSG_HW_RESPONSE)",
                                    m_info.uri)};
                if (std::find(ids.begin(), ids.end(), m.id) != ids.end()) return m;
                spdlog::trace("{}: skipping {} while waiting for {}", m_info.uri,
                              apt::message_name(m.id), what);
                continue;
            }
            // After stop(), the controller has one reply timeout to confirm with MOVE_STOPPED.
            const bool stopping = m_stop_requested;
            const auto stop_deadline =
                Clock::time_point(Clock::duration(m_stop_requested_at.load())) +
                m_options.reply_timeout;
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                (stopping ? std::min(deadline, stop_deadline) : deadline) - Clock::now());
            if (left.count() <= 0) {
                if (stopping)
                    return DeviceError{
                        DeviceErrorCode::Stopped,
                        fmt::format(
                            "{}: MGMSG_MOT_MOVE_STOP sent while waiting for {}; the controller "
                            "did not confirm with MGMSG_MOT_MOVE_STOPPED",
                            m_info.uri, what)};
                return DeviceError{
                    DeviceErrorCode::Timeout,
                    fmt::format("{}: no {} from the controller in time", m_info.uri, what)};
            }
            // Short reads, so a stop() from another thread is noticed within kStopPoll.
            auto bytes = m_port->read_some(std::min(left, kStopPoll));
            if (!bytes && bytes.error().code == DeviceErrorCode::Timeout && Clock::now() < deadline)
                continue;
            if (!bytes) {
                DeviceError e = bytes.error();
                if (e.code == DeviceErrorCode::Timeout)
                    e.message =
                        fmt::format("{}: no {} from the controller in time", m_info.uri, what);
                else
                    e.message =
                        fmt::format("{}: while waiting for {}: {}", m_info.uri, what, e.message);
                return e;
            }
            m_rx.insert(m_rx.end(), bytes.value().begin(), bytes.value().end());
        }
    }

    std::unique_ptr<BytePort> m_port;
    AptStageOptions m_options;
    StageInfo m_info;
    bool m_homed = false;
    std::vector<std::uint8_t> m_rx;
    std::mutex m_write_mutex;
    std::atomic<bool> m_in_motion{false};
    std::atomic<bool> m_stop_requested{false};
    std::atomic<Clock::rep> m_stop_requested_at{0};
};

}  // namespace

Result<std::unique_ptr<Stage>> open_apt_stage(std::unique_ptr<BytePort> port, std::string uri,
                                              const AptStageOptions& options) {
    if (!(options.counts_per_degree > 0.0))
        return DeviceError{DeviceErrorCode::InvalidArgument,
                           fmt::format("{}: counts per degree must be positive", uri)};
    auto stage = std::make_unique<AptStage>(std::move(port), std::move(uri), options);
    if (auto s = stage->initialise(); !s) return s.error();
    return std::unique_ptr<Stage>(std::move(stage));
}

}  // namespace tirpol::acquisition
