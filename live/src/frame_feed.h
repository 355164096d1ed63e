#pragma once
/// \file frame_feed.h
/// The live view's grab thread: the only reader of the camera. Every frame goes (a) into a
/// LatestSlot that displays sample at their own pace and (b) to every open FrameTap, unbounded, for
/// consumers that need every frame in order (the polarizer cycle, a capture plan). Also measures
/// the delivered frame rate and keeps the FPA temperature history.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "latest_slot.h"
#include "tirpol/acquisition/camera.h"

namespace tirpol::live {

/// Every frame the feed grabs after the tap was opened, in order, until the tap is destroyed.
class FrameTap {
public:
    /// The oldest frame not yet taken, waiting at most `timeout` (DeviceErrorCode::Timeout after).
    acquisition::Result<acquisition::Frame> next(std::chrono::milliseconds timeout);
    /// Frames waiting to be taken.
    std::size_t pending() const;
    void push(const acquisition::Frame& frame);
    /// Drops every waiting frame (a consumer that starts a new step after a pause).
    void clear();

private:
    mutable std::mutex m_mutex;
    std::condition_variable m_pushed;
    std::deque<acquisition::Frame> m_frames;
};

struct FeedStatistics {
    std::uint64_t delivered = 0, dropped = 0, incomplete = 0;  ///< the camera's own counts
    std::uint64_t grabbed = 0;                                 ///< frames this feed handed on
    std::optional<double> frame_rate_hz;  ///< frames received per second over the last ~2 s
    std::string last_error;               ///< the last grab error other than a timeout, if any
};

struct FpaSample {
    double time_s = 0.0;  ///< seconds since the feed started
    double temperature_k = 0.0;
};

class FrameFeed {
public:
    /// `camera` must outlive the feed. Keeps at most `fpa_history_samples` FPA samples (one a
    /// second).
    explicit FrameFeed(acquisition::Camera& camera, std::size_t fpa_history_samples = 3600);
    ~FrameFeed();
    FrameFeed(const FrameFeed&) = delete;
    FrameFeed& operator=(const FrameFeed&) = delete;

    /// Starts the camera and the grab thread.
    acquisition::Status start();
    /// Stops the grab thread and the camera.
    void stop();

    const acquisition::CameraInfo& camera_info() const { return m_info; }
    const LatestSlot<acquisition::Frame>& latest() const { return m_latest; }
    /// A tap that receives every frame grabbed from now on.
    std::shared_ptr<FrameTap> open_tap();
    /// The camera's counts as the grab thread read them after its last grab (the back ends'
    /// counters are not safe to read from another thread while it grabs), with the feed's own.
    FeedStatistics statistics() const;
    acquisition::StreamStatistics camera_statistics() const;
    std::vector<FpaSample> fpa_history() const;
    /// The last FPA temperature recorded (at most a second old), if the camera reports one.
    std::optional<double> fpa_temperature_k() const;

private:
    void run();
    void record_fpa(const acquisition::Frame& frame);

    acquisition::Camera& m_camera;
    acquisition::CameraInfo m_info;
    std::size_t m_fpa_capacity;
    LatestSlot<acquisition::Frame> m_latest;
    mutable std::mutex m_mutex;  ///< guards everything below
    std::vector<std::weak_ptr<FrameTap>> m_taps;
    std::deque<std::int64_t> m_recent_ns;  ///< reception times of the last ~2 s
    std::uint64_t m_grabbed = 0;
    acquisition::StreamStatistics m_camera_stats;
    std::string m_last_error;
    std::deque<FpaSample> m_fpa;
    std::chrono::steady_clock::time_point m_started, m_next_fpa;
    std::atomic<bool> m_running{false};
    std::thread m_thread;
};

}  // namespace tirpol::live
