#include "tirpol/acquisition/internal/lepton_control.h"

#include <fmt/format.h>

#include <thread>

namespace tirpol::acquisition {

namespace {
using Clock = std::chrono::steady_clock;
// LEP_SYS_STATUS_E (IDD 110-0144): the FFC status attribute.
constexpr std::int32_t kSysStatusReady = 0;
}  // namespace

LeptonControl::LeptonControl(std::unique_ptr<LeptonXu> xu, LeptonControlOptions options)
    : m_xu(std::move(xu)), m_options(options) {}

Result<std::vector<std::uint16_t>> LeptonControl::get(std::uint16_t command_id, std::size_t words) {
    const auto unit = lepton::xu_unit(command_id);
    if (!unit)
        return DeviceError{DeviceErrorCode::InvalidArgument,
                           fmt::format("{}: Lepton command 0x{:04X} is in no module PureThermal "
                                       "maps to an extension unit",
                                       m_xu->name(), command_id)};
    std::vector<std::uint8_t> bytes(words * 2);
    if (auto s = m_xu->get(*unit, lepton::xu_selector(command_id), bytes); !s)
        return DeviceError{s.error().code,
                           fmt::format("Lepton GET 0x{:04X}: {}", command_id, s.error().message)};
    return lepton::bytes_to_words(bytes);
}

Status LeptonControl::set(std::uint16_t command_id, std::span<const std::uint16_t> words) {
    const auto unit = lepton::xu_unit(command_id);
    if (!unit)
        return DeviceError{DeviceErrorCode::InvalidArgument,
                           fmt::format("{}: Lepton command 0x{:04X} is in no mapped module",
                                       m_xu->name(), command_id)};
    const auto bytes = lepton::words_to_bytes(words);
    if (auto s = m_xu->set(*unit, lepton::xu_selector(command_id), bytes); !s)
        return DeviceError{s.error().code,
                           fmt::format("Lepton SET 0x{:04X}: {}", command_id, s.error().message)};
    return ok_status();
}

Status LeptonControl::run(std::uint16_t command_id) {
    const auto unit = lepton::xu_unit(command_id);
    if (!unit)
        return DeviceError{DeviceErrorCode::InvalidArgument,
                           fmt::format("{}: Lepton command 0x{:04X} is in no mapped module",
                                       m_xu->name(), command_id)};
    // The board runs a command on a one-byte SET_CUR of its selector (the byte's value is unused).
    const std::uint8_t selector = lepton::xu_selector(command_id);
    const std::uint8_t byte[1] = {selector};
    if (auto s = m_xu->set(*unit, selector, byte); !s)
        return DeviceError{s.error().code,
                           fmt::format("Lepton RUN 0x{:04X}: {}", command_id, s.error().message)};
    return ok_status();
}

Status LeptonControl::set_tlinear(bool enabled, LeptonTLinearResolution resolution) {
    if (auto s = set(lepton::kRadTLinearResolution,
                     lepton::u32_words(static_cast<std::uint32_t>(resolution)));
        !s)
        return s;
    return set(lepton::kRadTLinearEnable, lepton::u32_words(enabled ? 1u : 0u));
}

Result<bool> LeptonControl::tlinear_enabled() {
    auto w = get(lepton::kRadTLinearEnable, 2);
    if (!w) return w.error();
    return lepton::u32_of(w.value(), 0) != 0;
}

Result<LeptonTLinearResolution> LeptonControl::tlinear_resolution() {
    auto w = get(lepton::kRadTLinearResolution, 2);
    if (!w) return w.error();
    const std::uint32_t v = lepton::u32_of(w.value(), 0);
    if (v > 1)
        return DeviceError{DeviceErrorCode::BadReply,
                           fmt::format("{}: TLinear resolution {} (expected 0 = 0.1 K or "
                                       "1 = 0.01 K)",
                                       m_xu->name(), v)};
    return static_cast<LeptonTLinearResolution>(v);
}

Result<lepton::FfcShutterMode> LeptonControl::ffc_shutter_mode() {
    auto w = get(lepton::kSysFfcShutterMode, 16);
    if (!w) return w.error();
    auto mode = lepton::decode_ffc_shutter_mode(w.value());
    if (!mode || mode->mode > lepton::FfcShutterMode::External)
        return DeviceError{DeviceErrorCode::BadReply,
                           fmt::format("{}: FFC shutter mode object with mode {} (expected 0 "
                                       "manual, 1 auto or 2 external)",
                                       m_xu->name(), mode ? mode->mode : 0u)};
    return *mode;
}

Status LeptonControl::set_ffc_mode(lepton::FfcShutterMode::Mode mode) {
    // Read, change the mode, write back: the object also holds the period and the temperature
    // threshold the operator may have set.
    auto current = ffc_shutter_mode();
    if (!current) return current.error();
    lepton::FfcShutterMode m = current.value();
    m.mode = mode;
    return set(lepton::kSysFfcShutterMode, lepton::encode_ffc_shutter_mode(m));
}

Status LeptonControl::set_telemetry(bool enabled) {
    return set(lepton::kSysTelemetryEnable, lepton::u32_words(enabled ? 1u : 0u));
}

Status LeptonControl::set_telemetry_location(LeptonTelemetryLocation location) {
    return set(lepton::kSysTelemetryLocation,
               lepton::u32_words(location == LeptonTelemetryLocation::Footer ? 1u : 0u));
}

Result<std::unique_ptr<LeptonControl>> open_lepton_control(std::unique_ptr<LeptonXu> xu,
                                                           LeptonControlOptions options) {
    const std::string name = xu->name();
    auto control = std::make_unique<LeptonControl>(std::move(xu), options);
    auto answer = [&](Status s, const char* what) -> Status {
        if (s) return s;
        return DeviceError{s.error().code, fmt::format("{}: no Lepton answered ({}): {}", name,
                                                       what, s.error().message)};
    };
    if (auto mode = control->ffc_shutter_mode(); !mode)
        return answer(mode.error(), "reading its FFC shutter mode").error();
    if (auto s = answer(control->set_telemetry_location(LeptonTelemetryLocation::Footer),
                        "setting the telemetry location");
        !s)
        return s.error();
    if (auto s = answer(control->set_telemetry(true), "enabling telemetry"); !s) return s.error();
    return control;
}

void LeptonControl::observe_telemetry(const lepton::Telemetry& t) {
    std::lock_guard lock(m_mutex);
    // A new time of the last FFC: the core ran one; its frame counter now is the FFC's frame.
    if (!m_latest || m_latest->uptime_at_last_ffc_ms != t.uptime_at_last_ffc_ms)
        m_frame_at_last_ffc = t.frame_counter;
    m_latest = t;
}

Result<lepton::Telemetry> LeptonControl::latest_telemetry() {
    // Right after the video starts the first frame (and its telemetry) may still be on its way.
    const auto deadline = Clock::now() + m_options.ffc_timeout;
    for (;;) {
        {
            std::lock_guard lock(m_mutex);
            if (m_latest || Clock::now() >= deadline) break;
        }
        wait_a_little();
    }
    std::lock_guard lock(m_mutex);
    if (!m_latest)
        return DeviceError{DeviceErrorCode::NotSupported,
                           fmt::format("{}: no Lepton telemetry seen yet; enable telemetry "
                                       "(SYS telemetry enable) so that each frame carries it",
                                       m_xu->name())};
    return *m_latest;
}

Result<std::uint64_t> LeptonControl::frames_since_ffc() {
    auto t = latest_telemetry();
    if (!t) return t.error();
    std::lock_guard lock(m_mutex);
    return static_cast<std::uint64_t>(t.value().frame_counter - *m_frame_at_last_ffc);
}

Status LeptonControl::set_manual_ffc() { return set_ffc_mode(lepton::FfcShutterMode::Manual); }

Status LeptonControl::run_ffc_and_wait() {
    std::optional<std::uint32_t> ffc_time_before;
    {
        std::lock_guard lock(m_mutex);
        if (m_latest) ffc_time_before = m_latest->uptime_at_last_ffc_ms;
    }
    if (auto s = run(lepton::kSysRunFfc); !s) return s;
    const auto deadline = Clock::now() + m_options.ffc_timeout;
    for (;;) {
        auto w = get(lepton::kSysFfcStatus, 2);
        if (!w) return w.error();
        const auto status = static_cast<std::int32_t>(lepton::u32_of(w.value(), 0));
        if (status == kSysStatusReady) break;
        if (status < 0)
            return DeviceError{
                DeviceErrorCode::DeviceFault,
                fmt::format("{}: the Lepton reports FFC status {} (error)", m_xu->name(), status)};
        if (Clock::now() >= deadline)
            return DeviceError{DeviceErrorCode::Timeout,
                               fmt::format("{}: the Lepton's FFC still busy after {} ms",
                                           m_xu->name(), m_options.ffc_timeout.count())};
        wait_a_little();
    }
    // With telemetry flowing, wait for the frames to show the FFC too: the capture compares the
    // last-FFC marker before and after each cycle, and a marker that moved late would look like an
    // FFC inside the next cycle.
    if (!ffc_time_before) return ok_status();
    for (;;) {
        {
            std::lock_guard lock(m_mutex);
            if (m_latest->uptime_at_last_ffc_ms != *ffc_time_before) return ok_status();
        }
        if (Clock::now() >= deadline)
            return DeviceError{DeviceErrorCode::Timeout,
                               fmt::format("{}: the Lepton reported its FFC done, but the "
                                           "telemetry of the frames never showed it within {} ms",
                                           m_xu->name(), m_options.ffc_timeout.count())};
        wait_a_little();
    }
}

void LeptonControl::wait_a_little() {
    // Frames reach the telemetry only when someone grabs them: during the capture that is this
    // thread, so pull them here rather than sleep.
    if (m_pull)
        m_pull();
    else
        std::this_thread::sleep_for(m_options.ffc_poll);
}

void LeptonControl::set_frame_pull(std::function<void()> pull) { m_pull = std::move(pull); }

void LeptonControl::observe_frame(const Frame& frame) {
    if (!frame.telemetry) return;
    lepton::Telemetry t;
    t.uptime_ms = frame.telemetry->uptime_ms;
    t.status_bits = static_cast<std::uint32_t>(frame.telemetry->ffc_state & 0x3) << 4;
    t.frame_counter = frame.telemetry->device_frame_counter;
    t.fpa_temperature_k = frame.fpa_temperature_k.value_or(0.0);
    t.uptime_at_last_ffc_ms = frame.telemetry->uptime_at_last_ffc_ms;
    observe_telemetry(t);
}

Result<double> LeptonControl::fpa_temperature_k() {
    auto w = get(lepton::kSysFpaTemperatureKelvin, 1);
    if (!w) return w.error();
    return w.value()[0] / 100.0;
}

Result<std::uint64_t> LeptonControl::last_ffc_marker() {
    auto t = latest_telemetry();
    if (!t) return t.error();
    std::lock_guard lock(m_mutex);
    return static_cast<std::uint64_t>(*m_frame_at_last_ffc);
}

Result<std::uint64_t> LeptonControl::device_frame_count() {
    auto t = latest_telemetry();
    if (!t) return t.error();
    return static_cast<std::uint64_t>(t.value().frame_counter);
}

Result<FrameAudit::CoreState> LeptonControl::core_state() {
    static constexpr const char* kModes[] = {"manual", "auto", "external"};
    FrameAudit::CoreState state;
    auto mode = ffc_shutter_mode();
    if (!mode) return mode.error();
    state.ffc_mode = kModes[mode.value().mode];
    state.gain_mode = "";  // the Lepton's gain mode is not read here
    auto fpa = fpa_temperature_k();
    if (!fpa) return fpa.error();
    state.fpa_temperature_k = fpa.value();
    auto frames = device_frame_count();
    if (!frames) return frames.error();
    state.device_frame_count = static_cast<std::int64_t>(frames.value());
    auto last = last_ffc_marker();
    if (!last) return last.error();
    state.last_ffc_frame_count = static_cast<std::int64_t>(last.value());
    return state;
}

}  // namespace tirpol::acquisition
