#pragma once
// Keeps flat-field corrections out of polarizer cycles (ffc.h): schedules them between cycles
// through the core's control link and looks for the offset step of one that happened inside a cycle
// anyway.

#include <map>
#include <optional>
#include <string>

#include "tirpol/acquisition/camera.h"
#include "tirpol/acquisition/capture.h"
#include "tirpol/core/session.h"

namespace tirpol::acquisition::detail {

class FfcGuard {
public:
    explicit FfcGuard(const FfcOptions& options);

    /// Before each attempt of a cycle (plan repeat `repeat`, the `cycles_started`-th cycle of this
    /// run, 0-based; `retry` after a detection). Runs the FFC the schedule asks for (always before
    /// a retry when there is a link) and returns its event; nullopt when none was due.
    Result<std::optional<FfcEvent>> before_cycle(int repeat, int cycles_started, bool retry);
    /// Starts a step's statistics.
    void begin_step();
    /// A kept frame of the current step: the reason, when its mean jumps from the step's mean so
    /// far (without a link only).
    std::optional<std::string> observe(const Frame& frame);
    /// Ends the step at `angle_deg` (its mean of frame means is kept for the cycle checks).
    void end_step(double angle_deg);
    /// After the cycle's last step: the event of an FFC found in the cycle (with a link: its
    /// last-FFC frame count moved; without: the frame statistics of ffc.h), to be taken again, or
    /// nullopt (the cycle is accepted and becomes the reference for the next one).
    Result<std::optional<FfcEvent>> end_cycle(int repeat);
    /// Forgets the current cycle's steps (after a detection within a step).
    void abandon_cycle();
    /// An event for a detection within a step.
    FfcEvent detected(int repeat, std::string reason);
    const FfcOptions& options() const { return m_options; }

private:
    FfcEvent event(FfcEvent::Kind kind, int repeat, std::string reason);

    FfcOptions m_options;
    bool m_manual_set = false;
    std::optional<double> m_fpa_at_last_ffc_k;
    std::optional<std::uint64_t> m_marker_at_cycle_start;
    double m_step_sum = 0.0;
    int m_step_frames = 0;
    std::map<long, double> m_cycle_means;      ///< angle in millidegrees → step mean, this cycle
    std::map<long, double> m_reference_means;  ///< ... of the last accepted cycle
};

}  // namespace tirpol::acquisition::detail
