#include "tirpol/acquisition/internal/blackbody_wait.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <thread>

#include "tirpol/core/radiometry.h"

namespace tirpol::acquisition {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}
}  // namespace

Result<SetPointReached> bring_blackbody_to(BlackbodyController& controller, double set_point_k,
                                           const BlackbodyStabilityCriterion& criterion,
                                           const std::function<bool()>& should_stop) {
    const auto start = Clock::now();
    if (auto s = controller.set_temperature_k(set_point_k); !s) return s.error();
    std::optional<Clock::time_point> good_since;
    const auto poll = std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(criterion.poll_s));
    for (auto next = start;; next += poll) {
        std::this_thread::sleep_until(next);
        if (should_stop && should_stop())
            return DeviceError{
                DeviceErrorCode::Stopped,
                fmt::format("waiting for the blackbody to reach {:.2f} K was interrupted",
                            set_point_k)};
        auto status = controller.status();
        if (!status) return status.error();
        const BlackbodyStatus& s = status.value();
        const bool good =
            s.stable && std::abs(s.temperature_k - set_point_k) <= criterion.tolerance_k;
        if (!good)
            good_since.reset();
        else if (!good_since)
            good_since = Clock::now();
        if (good_since && seconds_since(*good_since) >= criterion.stable_for_s)
            return SetPointReached{seconds_since(start), s};
        if (seconds_since(start) > criterion.timeout_s)
            return DeviceError{
                DeviceErrorCode::Timeout,
                fmt::format("{}: set-point {:.2f} K ({:.2f} °C) not stable within ±{:g} K for {:g} "
                            "s after {:g} s; "
                            "last reading {:.3f} K, stability flag {}",
                            controller.info().uri, set_point_k, set_point_k - kZeroCelsiusK,
                            criterion.tolerance_k, criterion.stable_for_s, criterion.timeout_s,
                            s.temperature_k, s.stable ? 1 : 0)};
        if (Clock::now() > next + poll)
            next = Clock::now() - poll;  // a slow reply: no burst of catch-up polls
    }
}

void BlackbodyReadingLog::add(const BlackbodyStatus& status) {
    m_temperatures_k.push_back(status.temperature_k);
    m_all_stable = m_all_stable && status.stable;
}

BlackbodyReadings BlackbodyReadingLog::summary() const {
    BlackbodyReadings r;
    r.set_point_k = m_set_point_k;
    r.wait_s = m_wait_s;
    r.readings = static_cast<std::int64_t>(m_temperatures_k.size());
    r.stable = m_all_stable;
    if (m_temperatures_k.empty()) return r;
    const double n = static_cast<double>(m_temperatures_k.size());
    r.mean_k = std::accumulate(m_temperatures_k.begin(), m_temperatures_k.end(), 0.0) / n;
    double ss = 0.0;
    for (double t : m_temperatures_k) ss += (t - r.mean_k) * (t - r.mean_k);
    r.std_k = m_temperatures_k.size() > 1 ? std::sqrt(ss / (n - 1.0)) : 0.0;
    const auto [lo, hi] = std::minmax_element(m_temperatures_k.begin(), m_temperatures_k.end());
    r.min_k = *lo;
    r.max_k = *hi;
    // The mean of rounded readings can fall a rounding error outside [min, max].
    r.mean_k = std::clamp(r.mean_k, r.min_k, r.max_k);
    return r;
}

}  // namespace tirpol::acquisition
