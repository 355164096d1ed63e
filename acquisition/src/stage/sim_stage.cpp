#include "tirpol/acquisition/sim_stage.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "move_preconditions.h"
#include "tirpol/acquisition/angles.h"

namespace tirpol::acquisition {

namespace {

class SimulatedStage final : public Stage {
public:
    SimulatedStage(std::string uri, SimulatedStageOptions options) : m_options(options), m_angle_deg(wrap_degrees(options.start_angle_deg)) {
        m_info = {std::move(uri), "tirpol", "simulated rotation stage", "SIM-0001", "1.0", options.counts_per_degree};
    }
    StageInfo info() const override { return m_info; }
    bool is_homed() const override { return m_homed; }

    Status home(std::chrono::milliseconds timeout) override {
        if (auto s = travel(0.0, timeout); !s) return s;
        m_homed = true;
        return ok_status();
    }

    Status move_absolute(double angle_deg, std::chrono::milliseconds timeout) override {
        if (auto s = detail::check_absolute_move(m_info.uri, m_homed, angle_deg); !s) return s;
        ++m_moves;
        if (m_options.fail_on_move && *m_options.fail_on_move == m_moves)
            return DeviceError{DeviceErrorCode::DeviceFault, fmt::format("{}: injected fault on move {}", m_info.uri, m_moves)};
        return travel(wrap_degrees(angle_deg), timeout);
    }

    Result<double> position_deg() override {
        // Quantised to the stage's counts, as a real encoder reads back.
        return wrap_degrees(std::round(m_angle_deg * m_options.counts_per_degree) / m_options.counts_per_degree);
    }

    Status stop() override {
        m_stop_requested = true;
        return ok_status();
    }

private:
    /// Turns towards `target_deg` at the set speed, watching for stop() every few milliseconds.
    Status travel(double target_deg, std::chrono::milliseconds timeout) {
        using Clock = std::chrono::steady_clock;
        m_stop_requested = false;
        if (m_options.deg_per_s > 0.0) {
            const double from_deg = m_angle_deg;
            const double seconds = std::abs(target_deg - from_deg) / m_options.deg_per_s;
            const auto needed = std::chrono::duration<double>(seconds);
            const auto start = Clock::now();
            const auto end = start + std::chrono::duration_cast<Clock::duration>(
                                         std::min<std::chrono::duration<double>>(needed, timeout));
            for (auto now = start; now < end; now = Clock::now()) {
                if (m_stop_requested) {
                    const double fraction = std::chrono::duration<double>(now - start).count() / seconds;
                    m_angle_deg = from_deg + (target_deg - from_deg) * fraction;
                    return DeviceError{DeviceErrorCode::Stopped,
                                       fmt::format("{}: stopped at {:.3f}° on the way to {:.3f}°", m_info.uri,
                                                   m_angle_deg, target_deg)};
                }
                std::this_thread::sleep_for(std::min<Clock::duration>(std::chrono::milliseconds(5), end - now));
            }
            if (needed > timeout)
                return DeviceError{DeviceErrorCode::Timeout, fmt::format("{}: move needs {:.2f} s, timeout {} ms",
                                                                         m_info.uri, seconds, timeout.count())};
        }
        m_angle_deg = target_deg;
        return ok_status();
    }

    SimulatedStageOptions m_options;
    StageInfo m_info;
    double m_angle_deg;
    bool m_homed = false;
    int m_moves = 0;
    std::atomic<bool> m_stop_requested{false};  ///< set by stop() from any thread
};

}  // namespace

std::unique_ptr<Stage> make_simulated_stage(std::string uri, const SimulatedStageOptions& options) {
    return std::make_unique<SimulatedStage>(std::move(uri), options);
}

}  // namespace tirpol::acquisition
