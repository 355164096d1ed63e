#include "frame_feed.h"

namespace tirpol::live {

using namespace acquisition;

namespace {
/// The frame rate is measured over this much reception time.
constexpr std::int64_t kRateWindowNs = 2'000'000'000;
constexpr std::chrono::milliseconds kGrabTimeout{500};
}  // namespace

Result<Frame> FrameTap::next(std::chrono::milliseconds timeout) {
    std::unique_lock lock(m_mutex);
    if (!m_pushed.wait_for(lock, timeout, [&] { return !m_frames.empty(); }))
        return DeviceError{DeviceErrorCode::Timeout, "live view: no frame from the camera within " +
                                                         std::to_string(timeout.count()) + " ms"};
    Frame frame = std::move(m_frames.front());
    m_frames.pop_front();
    return frame;
}

std::size_t FrameTap::pending() const {
    std::lock_guard lock(m_mutex);
    return m_frames.size();
}

void FrameTap::push(const Frame& frame) {
    {
        std::lock_guard lock(m_mutex);
        m_frames.push_back(frame);
    }
    m_pushed.notify_one();
}

void FrameTap::clear() {
    std::lock_guard lock(m_mutex);
    m_frames.clear();
}

FrameFeed::FrameFeed(Camera& camera, std::size_t fpa_history_samples)
    : m_camera(camera), m_info(camera.info()), m_fpa_capacity(fpa_history_samples) {}

FrameFeed::~FrameFeed() { stop(); }

Status FrameFeed::start() {
    if (m_running) return ok_status();
    if (auto s = m_camera.start(); !s) return s;
    m_started = m_next_fpa = std::chrono::steady_clock::now();
    m_running = true;
    m_thread = std::thread([this] { run(); });
    return ok_status();
}

void FrameFeed::stop() {
    if (!m_running.exchange(false)) return;
    m_thread.join();
    (void)m_camera.stop();
}

std::shared_ptr<FrameTap> FrameFeed::open_tap() {
    auto tap = std::make_shared<FrameTap>();
    std::lock_guard lock(m_mutex);
    m_taps.push_back(tap);
    return tap;
}

void FrameFeed::run() {
    while (m_running) {
        auto grabbed = m_camera.grab(kGrabTimeout);
        const StreamStatistics camera_stats = m_camera.statistics();
        if (!grabbed) {
            std::lock_guard lock(m_mutex);
            m_camera_stats = camera_stats;
            if (grabbed.error().code != DeviceErrorCode::Timeout)
                m_last_error = grabbed.error().message;
            continue;
        }
        auto frame = std::make_shared<const Frame>(std::move(grabbed.value()));
        record_fpa(*frame);
        std::vector<std::shared_ptr<FrameTap>> taps;
        {
            std::lock_guard lock(m_mutex);
            ++m_grabbed;
            m_camera_stats = camera_stats;
            m_recent_ns.push_back(frame->host_timestamp_ns);
            while (m_recent_ns.size() > 2 &&
                   m_recent_ns.back() - m_recent_ns.front() > kRateWindowNs)
                m_recent_ns.pop_front();
            std::erase_if(m_taps, [](const auto& t) { return t.expired(); });
            for (const auto& t : m_taps)
                if (auto tap = t.lock()) taps.push_back(std::move(tap));
        }
        for (const auto& tap : taps) tap->push(*frame);
        m_latest.publish(std::move(frame));
    }
}

void FrameFeed::record_fpa(const Frame& frame) {
    const auto now = std::chrono::steady_clock::now();
    if (now < m_next_fpa) return;
    m_next_fpa = now + std::chrono::seconds(1);
    // The frame's own stamp when the back end attaches one; else a register read (once a second).
    const std::optional<double> t =
        frame.fpa_temperature_k ? frame.fpa_temperature_k : m_camera.device_temperature_k();
    if (!t) return;
    std::lock_guard lock(m_mutex);
    m_fpa.push_back({std::chrono::duration<double>(now - m_started).count(), *t});
    while (m_fpa.size() > m_fpa_capacity) m_fpa.pop_front();
}

StreamStatistics FrameFeed::camera_statistics() const {
    std::lock_guard lock(m_mutex);
    return m_camera_stats;
}

std::optional<double> FrameFeed::fpa_temperature_k() const {
    std::lock_guard lock(m_mutex);
    if (m_fpa.empty()) return std::nullopt;
    return m_fpa.back().temperature_k;
}

FeedStatistics FrameFeed::statistics() const {
    FeedStatistics s;
    std::lock_guard lock(m_mutex);
    s.delivered = m_camera_stats.delivered;
    s.dropped = m_camera_stats.dropped;
    s.incomplete = m_camera_stats.incomplete;
    s.grabbed = m_grabbed;
    s.last_error = m_last_error;
    if (m_recent_ns.size() >= 2 && m_recent_ns.back() > m_recent_ns.front())
        s.frame_rate_hz = static_cast<double>(m_recent_ns.size() - 1) * 1e9 /
                          static_cast<double>(m_recent_ns.back() - m_recent_ns.front());
    return s;
}

std::vector<FpaSample> FrameFeed::fpa_history() const {
    std::lock_guard lock(m_mutex);
    return {m_fpa.begin(), m_fpa.end()};
}

}  // namespace tirpol::live
