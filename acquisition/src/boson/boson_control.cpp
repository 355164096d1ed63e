#include "tirpol/acquisition/internal/boson_control.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <thread>

#include "tirpol/acquisition/internal/serial_port.h"

namespace tirpol::acquisition {

namespace {
using Clock = std::chrono::steady_clock;
using namespace boson;

constexpr double kZeroCelsiusK = 273.15;

std::vector<std::uint8_t> be32(std::int32_t value) {
    std::vector<std::uint8_t> out;
    append_u32(out, static_cast<std::uint32_t>(value));
    return out;
}
}  // namespace

BosonControl::BosonControl(std::unique_ptr<BytePort> port, std::string name,
                           BosonControlOptions options)
    : m_port(std::move(port)), m_name(std::move(name)), m_options(options) {}

Result<std::vector<std::uint8_t>> BosonControl::transact(std::uint32_t function,
                                                         std::vector<std::uint8_t> data,
                                                         std::size_t reply_bytes) {
    const std::uint32_t previous = m_sequence;
    m_sequence = next_sequence(m_sequence);
    const std::uint32_t sequence = m_sequence;
    const char* fname = function_name(function);
    if (auto s = m_port->write(encode_command({sequence, function, std::move(data)}),
                               m_options.reply_timeout);
        !s)
        return s.error();
    const auto deadline = Clock::now() + m_options.reply_timeout;
    for (;;) {
        const auto now = Clock::now();
        if (now >= deadline)
            return DeviceError{
                DeviceErrorCode::Timeout,
                fmt::format(
                    "{}: no reply to {} (sequence {}) within {} ms: the core stopped answering",
                    m_name, fname, sequence, m_options.reply_timeout.count())};
        auto bytes = m_port->read_some(
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now) +
            std::chrono::milliseconds(1));
        if (!bytes) {
            if (bytes.error().code == DeviceErrorCode::Timeout) continue;
            return bytes.error();
        }
        for (const DecodedFrame& frame : m_decoder.feed(bytes.value())) {
            if (frame.status != FrameStatus::Ok)
                return DeviceError{DeviceErrorCode::BadReply,
                                   fmt::format("{}: the reply to {} (sequence {}) is damaged: {}",
                                               m_name, fname, sequence, describe(frame))};
            if (frame.channel != kCommandChannel)
                continue;  // other channels carry no command replies
            const auto reply = parse_reply(frame.payload);
            if (!reply)
                return DeviceError{
                    DeviceErrorCode::BadReply,
                    fmt::format(
                        "{}: the reply to {} has {} payload bytes, fewer than the {}-byte header",
                        m_name, fname, frame.payload.size(), kHeaderSize)};
            if (reply->sequence != sequence) {
                // An earlier command that timed out may still be answered late: skip that answer.
                if (reply->sequence != 0 && reply->sequence <= previous) {
                    spdlog::debug("{}: skipping a late reply (sequence {}) while waiting for {}",
                                  m_name, reply->sequence, sequence);
                    continue;
                }
                return DeviceError{
                    DeviceErrorCode::BadReply,
                    fmt::format("{}: the reply to {} carries sequence {}, the command had {}",
                                m_name, fname, reply->sequence, sequence)};
            }
            if (reply->function != function)
                return DeviceError{
                    DeviceErrorCode::BadReply,
                    fmt::format("{}: the reply to {} (sequence {}) names {} instead", m_name, fname,
                                sequence, function_name(reply->function))};
            if (reply->status != kSuccess)
                return DeviceError{DeviceErrorCode::DeviceFault,
                                   fmt::format("{}: {} failed: {}", m_name, fname,
                                               return_code_name(reply->status))};
            if (reply->data.size() < reply_bytes)
                return DeviceError{DeviceErrorCode::BadReply,
                                   fmt::format("{}: the reply to {} has {} data bytes, expected {}",
                                               m_name, fname, reply->data.size(), reply_bytes)};
            return reply->data;
        }
    }
}

Result<std::int32_t> BosonControl::get_i32(std::uint32_t function) {
    auto data = transact(function, {}, 4);
    if (!data) return data.error();
    return static_cast<std::int32_t>(read_u32(data.value(), 0));
}

Result<std::uint32_t> BosonControl::get_u32(std::uint32_t function) {
    auto data = transact(function, {}, 4);
    if (!data) return data.error();
    return read_u32(data.value(), 0);
}

Result<std::int16_t> BosonControl::get_i16(std::uint32_t function) {
    auto data = transact(function, {}, 2);
    if (!data) return data.error();
    return static_cast<std::int16_t>(read_u16(data.value(), 0));
}

Status BosonControl::set_i32(std::uint32_t function, std::int32_t value) {
    auto data = transact(function, be32(value), 0);
    if (!data) return data.error();
    return ok_status();
}

Result<std::uint32_t> BosonControl::camera_serial() { return get_u32(kBosonGetCameraSn); }

Result<std::string> BosonControl::part_number() {
    auto data = transact(kBosonGetCameraPn, {}, 20);
    if (!data) return data.error();
    std::string pn(data.value().begin(), data.value().begin() + 20);
    while (!pn.empty() && (pn.back() == '\0' || pn.back() == ' ')) pn.pop_back();
    if (std::any_of(pn.begin(), pn.end(), [](char c) { return c < 0x20 || c > 0x7E; }))
        return DeviceError{
            DeviceErrorCode::BadReply,
            fmt::format("{}: BOSON_GETCAMERAPN returned non-printable bytes (expected ASCII)",
                        m_name)};
    return pn;
}

Result<double> BosonControl::fpa_temperature_k() {
    auto deci_c = get_i16(kBosonLookupFpaTempDegCx10);
    if (!deci_c) return deci_c.error();
    return deci_c.value() / 10.0 + kZeroCelsiusK;
}

Result<FfcMode> BosonControl::ffc_mode() {
    auto v = get_i32(kBosonGetFfcMode);
    if (!v) return v.error();
    if (v.value() < 0 || v.value() > static_cast<std::int32_t>(FfcMode::ShutterTest))
        return DeviceError{
            DeviceErrorCode::BadReply,
            fmt::format("{}: BOSON_GETFFCMODE returned {} (expected 0 to 3)", m_name, v.value())};
    return static_cast<FfcMode>(v.value());
}

Status BosonControl::set_ffc_mode(FfcMode mode) {
    return set_i32(kBosonSetFfcMode, static_cast<std::int32_t>(mode));
}

Status BosonControl::run_ffc() {
    auto data = transact(kBosonRunFfc, {}, 0);
    if (!data) return data.error();
    return ok_status();
}

Status BosonControl::run_ffc_and_wait() {
    const auto started = Clock::now();
    auto before = last_ffc_frame_count();
    if (!before) return before.error();
    if (auto s = run_ffc(); !s) return s;
    for (;;) {
        auto state = ffc_state();
        if (!state) return state.error();
        const auto& s = state.value();
        // Complete and not running, and the core's last-FFC frame count moved on: this FFC, not an
        // older one.
        if (s.status == FfcStatus::Complete && !s.in_progress &&
            s.last_ffc_frame_count != before.value())
            return ok_status();
        if (Clock::now() - started > m_options.ffc_timeout)
            return DeviceError{
                DeviceErrorCode::Timeout,
                fmt::format("{}: the FFC did not complete within {} ms (status {}, in progress {})",
                            m_name, m_options.ffc_timeout.count(), static_cast<int>(s.status),
                            s.in_progress)};
        std::this_thread::sleep_for(m_options.ffc_poll);
    }
}

Result<FfcStatus> BosonControl::ffc_status() {
    auto v = get_i32(kBosonGetFfcStatus);
    if (!v) return v.error();
    if (v.value() < 0 || v.value() > static_cast<std::int32_t>(FfcStatus::Complete))
        return DeviceError{
            DeviceErrorCode::BadReply,
            fmt::format("{}: BOSON_GETFFCSTATUS returned {} (expected 0 to 3)", m_name, v.value())};
    return static_cast<FfcStatus>(v.value());
}

Result<bool> BosonControl::ffc_in_progress() {
    auto v = get_i16(kBosonGetFfcInProgress);
    if (!v) return v.error();
    return v.value() != 0;
}

Result<std::uint32_t> BosonControl::last_ffc_frame_count() {
    return get_u32(kBosonGetLastFfcFrameCount);
}
Result<std::uint32_t> BosonControl::frame_count() { return get_u32(kRoicGetFrameCount); }

Result<std::uint64_t> BosonControl::last_ffc_marker() {
    auto v = last_ffc_frame_count();
    if (!v) return v.error();
    return std::uint64_t{v.value()};
}

Result<std::uint64_t> BosonControl::device_frame_count() {
    auto v = frame_count();
    if (!v) return v.error();
    return std::uint64_t{v.value()};
}

Result<FrameAudit::CoreState> BosonControl::core_state() {
    static constexpr const char* kFfcModes[] = {"manual", "auto", "external", "shutter-test"};
    static constexpr const char* kGainModes[] = {"high", "low", "auto", "dual", "manual"};
    FrameAudit::CoreState state;
    auto ffc = ffc_mode();
    if (!ffc) return ffc.error();
    state.ffc_mode = kFfcModes[static_cast<int>(ffc.value())];
    auto gain = gain_mode();
    if (!gain) return gain.error();
    state.gain_mode = kGainModes[static_cast<int>(gain.value())];
    auto fpa = fpa_temperature_k();
    if (!fpa) return fpa.error();
    state.fpa_temperature_k = fpa.value();
    auto frames = frame_count();
    if (!frames) return frames.error();
    state.device_frame_count = frames.value();
    auto last = last_ffc_frame_count();
    if (!last) return last.error();
    state.last_ffc_frame_count = last.value();
    return state;
}

Result<BosonFfcState> BosonControl::ffc_state() {
    BosonFfcState state;
    auto status = ffc_status();
    if (!status) return status.error();
    state.status = status.value();
    auto running = ffc_in_progress();
    if (!running) return running.error();
    state.in_progress = running.value();
    auto frames = frame_count();
    if (!frames) return frames.error();
    state.frame_count = frames.value();
    auto last = last_ffc_frame_count();
    if (!last) return last.error();
    state.last_ffc_frame_count = last.value();
    return state;
}

Result<GainMode> BosonControl::gain_mode() {
    auto v = get_i32(kBosonGetGainMode);
    if (!v) return v.error();
    if (v.value() < 0 || v.value() > static_cast<std::int32_t>(GainMode::Manual))
        return DeviceError{
            DeviceErrorCode::BadReply,
            fmt::format("{}: BOSON_GETGAINMODE returned {} (expected 0 to 4)", m_name, v.value())};
    return static_cast<GainMode>(v.value());
}

Status BosonControl::set_gain_mode(GainMode mode) {
    return set_i32(kBosonSetGainMode, static_cast<std::int32_t>(mode));
}

Result<double> BosonControl::ffc_temperature_threshold_k() {
    auto data = transact(kBosonGetFfcTempThreshold, {}, 2);
    if (!data) return data.error();
    return read_u16(data.value(), 0) / 10.0;
}

Status BosonControl::set_ffc_temperature_threshold_k(double threshold_k) {
    if (!(threshold_k >= 0.0 && threshold_k <= 6553.5))
        return DeviceError{
            DeviceErrorCode::InvalidArgument,
            fmt::format(
                "{}: FFC temperature threshold {} K (expected 0 to 6553.5 K, in 0.1 K steps)",
                m_name, threshold_k)};
    std::vector<std::uint8_t> data;
    append_u16(data, static_cast<std::uint16_t>(std::lround(threshold_k * 10.0)));
    auto reply = transact(kBosonSetFfcTempThreshold, std::move(data), 0);
    if (!reply) return reply.error();
    return ok_status();
}

Result<std::unique_ptr<BosonControl>> open_boson_control(const std::string& port_path,
                                                         const std::string& uri,
                                                         BosonControlOptions options) {
    auto port = open_serial_port(port_path, SerialSettings{921600, false});
    if (!port) return port.error();
    if (auto s = port.value()->discard_input(); !s) return s.error();
    auto control = std::make_unique<BosonControl>(std::move(port.value()), uri, options);
    auto serial = control->camera_serial();
    if (!serial)
        return DeviceError{
            serial.error().code,
            fmt::format("{} (is a FLIR Boson on {}? it did not answer BOSON_GETCAMERASN)",
                        serial.error().message, port_path)};
    return control;
}

}  // namespace tirpol::acquisition
