#pragma once
/// \file capture_control.h
/// Runs a capture plan from the page: the session is written by acquisition::run_capture into a
/// SessionWriter, exactly as `tirpol acquire` does (same manifest, same files, resumable with
/// `tirpol acquire --resume` or from the page), reading frames through a TappedCamera so the live
/// view keeps streaming. The polarizer cycle is paused for the run. Stop works like Ctrl-C in
/// `tirpol acquire` (acquisition::StopOnInterrupt): the stage is told to stop, the run ends after
/// the current frame and every recorded step stays.

#include <atomic>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>

#include "frame_feed.h"
#include "polarizer_cycle.h"
#include "tirpol/acquisition/stage.h"

namespace tirpol::live {

struct CaptureRequest {
    std::filesystem::path plan;  ///< capture plan YAML
    std::filesystem::path
        output;  ///< session directory (new, or an interrupted session with resume)
    bool resume = false;
};

enum class CapturePhase { Idle, Running, Stopping, Complete, Stopped, Failed };
const char* to_string(CapturePhase phase);

struct CaptureState {
    CapturePhase phase = CapturePhase::Idle;
    std::size_t steps_total = 0;
    std::size_t steps_recorded = 0;  ///< in the session, read back from its manifest
    std::string output;
    std::string message;  ///< the summary, or the error (which says how to resume)
};

class CaptureControl {
public:
    /// `cycle` may be null (no stage cycling to pause). All must outlive this object.
    CaptureControl(FrameFeed& feed, acquisition::Stage& stage, PolarizerCycle* cycle);
    ~CaptureControl();
    CaptureControl(const CaptureControl&) = delete;
    CaptureControl& operator=(const CaptureControl&) = delete;

    /// Loads the plan and opens the session (new or resumed) before returning, so a bad plan, a
    /// non-empty directory or a session of another plan is a tirpol::Error here; then runs on a
    /// thread. Also an error while a capture is running.
    void start(const CaptureRequest& request);
    /// Asks a running capture to stop (returns at once; the state turns Stopped when it has).
    void stop();
    CaptureState state() const;

private:
    void finish(CapturePhase phase, std::string message);

    FrameFeed& m_feed;
    acquisition::Stage& m_stage;
    PolarizerCycle* m_cycle;
    mutable std::mutex m_mutex;  ///< guards m_state
    CaptureState m_state;
    std::atomic<bool> m_stop{false};
    std::thread m_thread;
};

}  // namespace tirpol::live
