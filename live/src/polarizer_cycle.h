#pragma once
/// \file polarizer_cycle.h
/// With a stage: turns the polarizer through its angles (0/45/90/135° by default) again and again
/// and publishes the Stokes image of each complete cycle. Frames are chosen as `tirpol acquire`
/// chooses them — acquisition::FrameGate keeps only frames exposed after the stage settled —
/// averaged with acquisition::FrameAverager, and reduced with calibration::reduce_stokes (ideal
/// analyzer at the angles read back from the stage), the code `tirpol reduce` uses.

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "display_frame.h"
#include "frame_feed.h"
#include "tirpol/acquisition/stage.h"
#include "tirpol/core/image.h"
#include "tirpol/live/live_server.h"

namespace tirpol::live {

struct CycleStatus {
    std::string state =
        "idle";  ///< "homing", "moving to 45°", "averaging 45° (2/4)", "paused", "failed"
    std::optional<double> angle_deg;  ///< the stage's last read-back angle
    std::uint64_t cycles = 0;         ///< complete cycles published
    std::string error;                ///< the last device error, if any
};

class PolarizerCycle {
public:
    /// `feed`, `stage` and `converter` must outlive the cycle. Throws tirpol::Error for options
    /// that cannot give a Stokes image (fewer than 3 angles, frames_per_angle < 1).
    PolarizerCycle(FrameFeed& feed, acquisition::Stage& stage, const DisplayConverter& converter,
                   CycleOptions options);
    ~PolarizerCycle();
    PolarizerCycle(const PolarizerCycle&) = delete;
    PolarizerCycle& operator=(const PolarizerCycle&) = delete;

    void start();
    void stop();
    /// Stops cycling and returns once the stage is no longer commanded by this object (a capture
    /// plan may then use it); resume() restarts with a fresh cycle.
    void pause();
    void resume();

    /// S0 S1 S2 DoLP AoP (+ *_std) of the latest complete cycle, in the converter's signal units.
    const LatestSlot<Image>& stokes() const { return m_stokes; }
    CycleStatus status() const;

private:
    void run();
    /// One full cycle; false when it was cut short (pause, stop, device error).
    bool run_cycle(FrameTap& tap);
    bool keep_going() const { return m_running && !m_pause_requested; }
    void set_state(std::string state, std::optional<double> angle_deg = std::nullopt);

    FrameFeed& m_feed;
    acquisition::Stage& m_stage;
    const DisplayConverter& m_converter;
    CycleOptions m_options;
    LatestSlot<Image> m_stokes;
    mutable std::mutex m_mutex;  ///< guards m_status, m_paused
    std::condition_variable m_changed;
    CycleStatus m_status;
    bool m_paused = false;  ///< the thread acknowledged a pause
    std::atomic<bool> m_running{false}, m_pause_requested{false};
    std::thread m_thread;
};

}  // namespace tirpol::live
