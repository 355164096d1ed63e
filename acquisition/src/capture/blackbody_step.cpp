#include "capture/blackbody_step.h"

#include <fmt/format.h>

#include <cmath>

namespace tirpol::acquisition::detail {

BlackbodyStep::BlackbodyStep(BlackbodyController& controller, const CaptureStep& step,
                             std::optional<double>& settled_set_point_k)
    : m_controller(controller),
      m_set_point_k(step.temperature_k.value()),
      m_criterion(step.blackbody_control.value()),
      m_settled(settled_set_point_k),
      m_log(m_set_point_k, 0.0) {}

Status BlackbodyStep::reach_set_point(const std::function<bool()>& should_stop) {
    if (m_settled == m_set_point_k)
        return ok_status();  // the same set-point at the next polarizer angle
    m_settled.reset();
    auto reached = bring_blackbody_to(m_controller, m_set_point_k, m_criterion, should_stop);
    if (!reached) return reached.error();
    m_settled = m_set_point_k;
    m_log = BlackbodyReadingLog(m_set_point_k, reached.value().wait_s);
    return ok_status();
}

Status BlackbodyStep::poll() {
    auto status = m_controller.status();
    if (!status) {
        m_settled.reset();
        return status.error();
    }
    m_log.add(status.value());
    m_worst_deviation_k =
        std::max(m_worst_deviation_k, std::abs(status.value().temperature_k - m_set_point_k));
    m_next_poll = std::chrono::steady_clock::now() +
                  std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                      std::chrono::duration<double>(m_criterion.poll_s));
    return ok_status();
}

Status BlackbodyStep::poll_if_due() {
    if (m_log.count() > 0 && std::chrono::steady_clock::now() < m_next_poll) return ok_status();
    return poll();
}

Status BlackbodyStep::finish() {
    if (auto s = poll(); !s) return s;
    if (m_worst_deviation_k > m_criterion.tolerance_k) {
        m_settled.reset();  // wait again before the next step at this set-point
        const BlackbodyReadings r = m_log.summary();
        return DeviceError{DeviceErrorCode::DeviceFault,
                           fmt::format("{}: left ±{:g} K of the set-point {:.2f} K while the "
                                       "frames were taken (readings {:.3f}–{:.3f} K); "
                                       "its frames are discarded",
                                       m_controller.info().uri, m_criterion.tolerance_k,
                                       m_set_point_k, r.min_k, r.max_k)};
    }
    return ok_status();
}

}  // namespace tirpol::acquisition::detail
