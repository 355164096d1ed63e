#include "tirpol/acquisition/frame_gate.h"

#include <algorithm>
#include <cmath>
#include <ctime>

namespace tirpol::acquisition {

namespace {
constexpr std::int64_t kUnknownPeriodNs =
    200'000'000;  ///< before any interval is seen: ≤ 5 Hz assumed
/// Intervals longer than this are pauses (the capture loop not grabbing, a software trigger waiting
/// for a move), not the camera's rate.
constexpr std::int64_t kPauseNs = 2'000'000'000;
}  // namespace

std::int64_t host_realtime_ns() {
    timespec ts{};
    clock_gettime(CLOCK_REALTIME, &ts);
    return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

FrameGate::FrameGate(std::optional<double> nominal_frame_rate_hz) {
    if (nominal_frame_rate_hz && *nominal_frame_rate_hz > 0.0 &&
        std::isfinite(*nominal_frame_rate_hz))
        m_nominal_period_ns = static_cast<std::int64_t>(std::llround(1e9 / *nominal_frame_rate_hz));
}

std::int64_t FrameGate::exposure_window_ns() const {
    // A camera may not reach the rate it reports (a fake asked for 1000 Hz delivers 60): the
    // shortest interval seen is a lower bound of the true period, so the longer of the two is the
    // safe one.
    std::int64_t period = kUnknownPeriodNs;
    if (m_nominal_period_ns && m_min_period_ns)
        period = std::max(*m_nominal_period_ns, *m_min_period_ns);
    else if (m_nominal_period_ns)
        period = *m_nominal_period_ns;
    else if (m_min_period_ns)
        period = *m_min_period_ns;
    return period + period / 2;
}

std::int64_t FrameGate::reception_ns(const Frame& frame) {
    if (frame.device_timestamp_ns == 0) return frame.host_timestamp_ns;
    // host − device = clock offset + this frame's latency. Its minimum over frames is the offset
    // plus the shortest latency: device + that minimum is when the frame would have arrived with no
    // host delay. The minimum may creep up by FrameGate::kOffsetCreepPerNs per ns of device time,
    // so a device clock slower than the host's (crystals differ by tens of ppm) is followed; a
    // faster one lowers the minimum.
    const std::int64_t offset = frame.host_timestamp_ns - frame.device_timestamp_ns;
    if (m_min_offset_ns && m_last_device_ns != 0 && frame.device_timestamp_ns > m_last_device_ns)
        *m_min_offset_ns += static_cast<std::int64_t>(
            FrameGate::kOffsetCreepPerNs *
            static_cast<double>(frame.device_timestamp_ns - m_last_device_ns));
    m_min_offset_ns = m_min_offset_ns ? std::min(*m_min_offset_ns, offset) : offset;
    m_last_device_ns = frame.device_timestamp_ns;
    return std::min(frame.host_timestamp_ns, frame.device_timestamp_ns + *m_min_offset_ns);
}

bool FrameGate::exposed_after(const Frame& frame, std::int64_t settle_end_ns) {
    const std::int64_t reception = reception_ns(frame);
    if (m_have_last && frame.frame_id > m_last_id && reception > m_last_ns) {
        const auto ids = frame.frame_id - m_last_id;
        const std::int64_t dt = reception - m_last_ns;
        if (dt < kPauseNs) {
            const auto per_id = dt / static_cast<std::int64_t>(ids);
            m_min_period_ns = m_min_period_ns ? std::min(*m_min_period_ns, per_id) : per_id;
            ++m_intervals;
            m_span_ns += dt;
        }
    }
    m_have_last = true;
    m_last_id = frame.frame_id;
    m_last_ns = reception;
    return reception - exposure_window_ns() >= settle_end_ns;
}

std::optional<double> FrameGate::delivered_rate_hz() const {
    if (m_span_ns <= 0 || m_intervals == 0) return std::nullopt;
    return static_cast<double>(m_intervals) * 1e9 / static_cast<double>(m_span_ns);
}

}  // namespace tirpol::acquisition
