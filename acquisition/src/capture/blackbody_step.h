#pragma once
// The blackbody controller's part of a capture step whose temperature it sets: bring it to the
// set-point (once per set-point in a run), poll it while the frames are taken, and check that it
// held the set-point throughout.

#include <chrono>
#include <functional>
#include <optional>

#include "tirpol/acquisition/capture_plan.h"
#include "tirpol/acquisition/internal/blackbody_wait.h"

namespace tirpol::acquisition::detail {

class BlackbodyStep {
public:
    /// `settled_set_point_k` is the set-point this run last brought the controller to (shared by
    /// steps).
    BlackbodyStep(BlackbodyController& controller, const CaptureStep& step,
                  std::optional<double>& settled_set_point_k);
    /// Sets and waits unless the previous controlled step of this run settled at the same
    /// set-point.
    Status reach_set_point(const std::function<bool()>& should_stop);
    /// Polls the controller when poll_s has passed since the last poll (call between frames).
    Status poll_if_due();
    /// A last reading; DeviceFault if any reading left the tolerance (the frames are then
    /// discarded).
    Status finish();
    BlackbodyReadings readings() const { return m_log.summary(); }

private:
    Status poll();
    BlackbodyController& m_controller;
    const double m_set_point_k;
    const BlackbodyStabilityCriterion m_criterion;
    std::optional<double>& m_settled;
    BlackbodyReadingLog m_log;
    std::chrono::steady_clock::time_point m_next_poll{};
    double m_worst_deviation_k = 0.0;
};

}  // namespace tirpol::acquisition::detail
