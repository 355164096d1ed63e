#include "polarizer_cycle.h"

#include <fmt/format.h>

#include <chrono>

#include "tirpol/acquisition/frame_gate.h"
#include "tirpol/calibration/stokes_reduction.h"
#include "tirpol/core/error.h"

namespace tirpol::live {

using namespace acquisition;

namespace {
std::chrono::milliseconds to_ms(double seconds) {
    return std::chrono::milliseconds(static_cast<std::int64_t>(seconds * 1000.0));
}
constexpr std::chrono::milliseconds kPausePoll{50};
}  // namespace

PolarizerCycle::PolarizerCycle(FrameFeed& feed, Stage& stage, const DisplayConverter& converter,
                               CycleOptions options)
    : m_feed(feed), m_stage(stage), m_converter(converter), m_options(std::move(options)) {
    if (m_options.angles_deg.size() < 3)
        fail("live view: a Stokes image needs at least 3 polarizer angles, got {}",
             m_options.angles_deg.size());
    if (m_options.frames_per_angle < 1)
        fail("live view: frames per angle must be at least 1, got {}", m_options.frames_per_angle);
}

PolarizerCycle::~PolarizerCycle() { stop(); }

void PolarizerCycle::start() {
    if (m_running.exchange(true)) return;
    m_thread = std::thread([this] { run(); });
}

void PolarizerCycle::stop() {
    if (!m_running.exchange(false)) return;
    (void)m_stage.stop();  // a move in progress returns at once instead of at its timeout
    m_thread.join();
}

void PolarizerCycle::pause() {
    m_pause_requested = true;
    std::unique_lock lock(m_mutex);
    m_changed.wait(lock, [&] { return m_paused || !m_running; });
}

void PolarizerCycle::resume() {
    m_pause_requested = false;
    m_changed.notify_all();
}

CycleStatus PolarizerCycle::status() const {
    std::lock_guard lock(m_mutex);
    return m_status;
}

void PolarizerCycle::set_state(std::string state, std::optional<double> angle_deg) {
    std::lock_guard lock(m_mutex);
    m_status.state = std::move(state);
    if (angle_deg) m_status.angle_deg = angle_deg;
}

void PolarizerCycle::run() {
    while (m_running) {
        if (m_pause_requested) {
            std::unique_lock lock(m_mutex);
            m_paused = true;
            m_status.state = "paused";
            m_changed.notify_all();
            m_changed.wait_for(lock, kPausePoll, [&] { return !m_pause_requested || !m_running; });
            m_paused = false;
            continue;
        }
        const auto tap = m_feed.open_tap();
        if (!run_cycle(*tap) && m_running && !m_pause_requested) {
            // A device error: show it and try again after a pause rather than hammering the stage.
            std::this_thread::sleep_for(std::chrono::seconds(1));
        }
    }
    std::lock_guard lock(m_mutex);
    m_status.state = "stopped";
    m_changed.notify_all();
}

bool PolarizerCycle::run_cycle(FrameTap& tap) {
    auto device_failed = [&](const std::string& what, const DeviceError& e) {
        std::lock_guard lock(m_mutex);
        if (e.code == DeviceErrorCode::Stopped && !keep_going())
            return false;  // our own stop(), not a fault
        m_status.state = "failed";
        m_status.error = fmt::format("{}: {}: {}", what, to_string(e.code), e.message);
        return false;
    };
    if (!m_stage.is_homed()) {
        set_state("homing");
        if (auto s = m_stage.home(to_ms(m_options.home_timeout_s)); !s)
            return device_failed("homing", s.error());
    }
    FrameGate gate(m_feed.camera_info().frame_rate_hz);
    std::vector<calibration::AnalyzerImage> images;
    std::vector<double> measured_deg;
    std::vector<double> frame_ids;  // first and last id averaged at each angle, in order
    for (const double angle : m_options.angles_deg) {
        if (!keep_going()) return false;
        set_state(fmt::format("moving to {:g}°", angle));
        if (auto s = m_stage.move_absolute(angle, to_ms(m_options.move_timeout_s)); !s)
            return device_failed(fmt::format("moving to {:g}°", angle), s.error());
        std::this_thread::sleep_for(to_ms(m_options.settle_s));
        const std::int64_t settle_end_ns = host_realtime_ns();
        auto position = m_stage.position_deg();
        if (!position) return device_failed("reading the angle", position.error());
        set_state(fmt::format("averaging {:g}°", angle), position.value());
        FrameAverager averager;
        std::optional<double> fpa_k;
        while (averager.count() < static_cast<std::uint64_t>(m_options.frames_per_angle)) {
            if (!keep_going()) return false;
            auto frame = tap.next(to_ms(m_options.frame_timeout_s));
            if (!frame) return device_failed("camera", frame.error());
            if (!gate.exposed_after(frame.value(), settle_end_ns))
                continue;  // exposed while the stage moved
            averager.add(frame.value());
            const auto id = static_cast<double>(frame.value().frame_id);
            if (averager.count() == 1) frame_ids.insert(frame_ids.end(), {id, id});
            frame_ids.back() = id;
            fpa_k = frame.value().fpa_temperature_k;
        }
        calibration::AnalyzerImage image;
        image.angle_deg = position.value();
        image.signal = m_converter.to_signal(averager.mean(), fpa_k);
        image.source = fmt::format("live {:g}°", angle);
        images.push_back(std::move(image));
        measured_deg.push_back(position.value());
    }
    calibration::ReductionOptions options;
    options.units = m_converter.unit() == DisplayUnit::Counts ? "counts" : "W/(m^2 sr)";
    try {
        auto stokes = std::make_shared<Image>(calibration::reduce_stokes(
            images, m_feed.camera_info().width, m_feed.camera_info().height,
            calibration::AnalyzerModel::ideal(measured_deg), nullptr, options));
        stokes->attributes()["cycle_frame_ids"] = frame_ids;
        m_stokes.publish(std::move(stokes));
    } catch (const Error& e) {
        std::lock_guard lock(m_mutex);
        m_status.state = "failed";
        m_status.error = std::string("Stokes reduction: ") + e.what();
        return false;
    }
    std::lock_guard lock(m_mutex);
    ++m_status.cycles;
    m_status.error.clear();
    return true;
}

}  // namespace tirpol::live
