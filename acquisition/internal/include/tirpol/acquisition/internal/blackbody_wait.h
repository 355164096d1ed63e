#pragma once
/// \file blackbody_wait.h
/// Bringing a blackbody controller to a set-point before frames are taken, and summarising what it
/// read while they were: the plate lags its set-point (a first-order response with a time constant
/// of minutes), and frames taken before it settles carry the lag into the calibration. Internal:
/// the capture loop calls it for a plan's controlled blackbody steps (BlackbodyStabilityCriterion
/// is in capture_plan.h).

#include <functional>
#include <optional>

#include "tirpol/acquisition/blackbody.h"
#include "tirpol/acquisition/capture_plan.h"
#include "tirpol/core/session.h"

namespace tirpol::acquisition {

struct SetPointReached {
    double wait_s = 0.0;  ///< from the set-point command until the criterion held
    BlackbodyStatus last;
};

/// Sends `set_point_k` and polls until `criterion` holds. Errors: the controller's own (a tripped
/// cutout, no reply, a garbled reply), Timeout after criterion.timeout_s ("set-point 313.15 K not
/// stable within ±0.05 K for 30 s after 1800 s; last reading 312.40 K, stability flag 0"), Stopped
/// when `should_stop` returns true (checked at every poll).
Result<SetPointReached> bring_blackbody_to(BlackbodyController& controller, double set_point_k,
                                           const BlackbodyStabilityCriterion& criterion,
                                           const std::function<bool()>& should_stop = {});

/// Accumulates the controller's readings while a record's frames are taken.
class BlackbodyReadingLog {
public:
    BlackbodyReadingLog(double set_point_k, double wait_s)
        : m_set_point_k(set_point_k), m_wait_s(wait_s) {}
    void add(const BlackbodyStatus& status);
    std::size_t count() const { return m_temperatures_k.size(); }
    /// The summary a session record keeps (count() ≥ 1).
    BlackbodyReadings summary() const;

private:
    double m_set_point_k, m_wait_s;
    std::vector<double> m_temperatures_k;
    bool m_all_stable = true;
};

}  // namespace tirpol::acquisition
