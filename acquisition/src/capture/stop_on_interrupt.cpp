#include <spdlog/spdlog.h>

#include "tirpol/acquisition/capture.h"

namespace tirpol::acquisition {

StopOnInterrupt::StopOnInterrupt(const std::atomic<bool>& interrupt,
                                 std::chrono::milliseconds grace, std::function<void()> on_overdue,
                                 std::chrono::milliseconds restop_period)
    : m_watcher(interrupt, [this] { return stop_stage(); },
                {restop_period, grace, std::move(on_overdue)}) {}

StopOnInterrupt::~StopOnInterrupt() = default;

bool StopOnInterrupt::stop_stage() {
    Stage* stage = m_stage.load();
    if (!stage) return false;
    if (auto s = stage->stop(); !s) spdlog::warn("stopping the stage: {}", s.error().message);
    ++m_stops_sent;
    return true;
}

}  // namespace tirpol::acquisition
