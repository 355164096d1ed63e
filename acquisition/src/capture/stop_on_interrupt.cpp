#include "tirpol/acquisition/stop_on_interrupt.h"

#include <spdlog/spdlog.h>

namespace tirpol::acquisition {

StopOnInterrupt::StopOnInterrupt(const std::atomic<bool>& interrupt,
                                 std::chrono::milliseconds grace, std::function<void()> on_overdue,
                                 std::chrono::milliseconds restop_period)
    : m_interrupt(interrupt),
      m_grace(grace),
      m_restop_period(restop_period),
      m_on_overdue(std::move(on_overdue)) {
    m_thread = std::thread([this] { run(); });
}

StopOnInterrupt::~StopOnInterrupt() {
    m_done = true;
    m_thread.join();
}

void StopOnInterrupt::run() {
    using Clock = std::chrono::steady_clock;
    constexpr auto kPoll = std::chrono::milliseconds(10);
    while (!m_done && !m_interrupt) std::this_thread::sleep_for(kPoll);
    if (m_done) return;
    const auto overdue_at = Clock::now() + m_grace;
    auto next_stop = Clock::now();
    while (!m_done) {
        const auto now = Clock::now();
        if (now >= overdue_at) {
            if (m_on_overdue) m_on_overdue();
            return;
        }
        if (Stage* stage = m_stage.load(); stage && now >= next_stop) {
            if (auto s = stage->stop(); !s)
                spdlog::warn("stopping the stage: {}", s.error().message);
            ++m_stops_sent;
            next_stop = now + m_restop_period;
        }
        std::this_thread::sleep_for(kPoll);
    }
}

}  // namespace tirpol::acquisition
