#include "tirpol/acquisition/internal/sim_stage.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <thread>

#include "move_preconditions.h"
#include "tirpol/acquisition/internal/angles.h"
#include "tirpol/core/error.h"

namespace tirpol::acquisition {

namespace {

class SimulatedStage final : public Stage {
public:
    SimulatedStage(std::string uri, SimulatedStageOptions options)
        : m_options(options),
          m_from_deg(wrap_degrees(options.start_angle_deg)),
          m_to_deg(m_from_deg) {
        m_info = {std::move(uri), "tirpol", "simulated rotation stage",
                  "SIM-0001",     "1.0",    options.counts_per_degree};
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
            return DeviceError{DeviceErrorCode::DeviceFault,
                               fmt::format("{}: injected fault on move {}", m_info.uri, m_moves)};
        return travel(wrap_degrees(angle_deg), timeout);
    }

    Result<double> position_deg() override {
        // Quantised to the stage's counts, as a real encoder reads back.
        return wrap_degrees(std::round(physical_angle_deg() * m_options.counts_per_degree) /
                            m_options.counts_per_degree);
    }

    /// Where the mount is now, moving at deg_per_s between the start and end of a move; any thread.
    double physical_angle_deg() const {
        std::lock_guard lock(m_mutex);
        return angle_at(Clock::now());
    }

    Status stop() override {
        m_stop_requested = true;
        return ok_status();
    }

private:
    using Clock = std::chrono::steady_clock;

    /// The trajectory at `t`; the caller holds m_mutex.
    double angle_at(Clock::time_point t) const {
        if (t >= m_move_end) return wrap_degrees(m_to_deg);
        const double f = std::chrono::duration<double>(t - m_move_start) /
                         std::chrono::duration<double>(m_move_end - m_move_start);
        return wrap_degrees(m_from_deg + (m_to_deg - m_from_deg) * std::clamp(f, 0.0, 1.0));
    }

    /// Ends the current move where the mount is now (a stop or a timeout); returns that angle.
    double halt() {
        std::lock_guard lock(m_mutex);
        const auto now = Clock::now();
        m_from_deg = m_to_deg = angle_at(now);
        m_move_end = now;
        return m_to_deg;
    }

    /// Turns towards `target_deg` at the set speed along a trajectory that simulated cameras read
    /// in time (physical_angle_deg), watching for stop() every few milliseconds.
    Status travel(double target_deg, std::chrono::milliseconds timeout) {
        m_stop_requested = false;
        const double from_deg = physical_angle_deg();
        if (m_options.deg_per_s > 0.0) {
            const double seconds = std::abs(target_deg - from_deg) / m_options.deg_per_s;
            const auto needed = std::chrono::duration<double>(seconds);
            const auto start = Clock::now();
            {
                std::lock_guard lock(m_mutex);
                m_from_deg = from_deg;
                m_to_deg = target_deg;
                m_move_start = start;
                m_move_end = start + std::chrono::duration_cast<Clock::duration>(needed);
            }
            const auto end = start + std::chrono::duration_cast<Clock::duration>(
                                         std::min<std::chrono::duration<double>>(needed, timeout));
            for (auto now = start; now < end; now = Clock::now()) {
                if (m_stop_requested) {
                    const double at_deg = halt();
                    return DeviceError{DeviceErrorCode::Stopped,
                                       fmt::format("{}: stopped at {:.3f}° on the way to {:.3f}°",
                                                   m_info.uri, at_deg, target_deg)};
                }
                std::this_thread::sleep_for(
                    std::min<Clock::duration>(std::chrono::milliseconds(5), end - now));
            }
            if (needed > timeout) {
                halt();
                return DeviceError{DeviceErrorCode::Timeout,
                                   fmt::format("{}: move needs {:.2f} s, timeout {} ms", m_info.uri,
                                               seconds, timeout.count())};
            }
        }
        std::lock_guard lock(m_mutex);
        m_from_deg = m_to_deg = target_deg;
        m_move_end = Clock::now();
        return ok_status();
    }

    SimulatedStageOptions m_options;
    StageInfo m_info;
    mutable std::mutex
        m_mutex;  ///< the trajectory is read by simulated cameras on their own threads
    double m_from_deg, m_to_deg;
    Clock::time_point m_move_start{}, m_move_end{};
    bool m_homed = false;
    int m_moves = 0;
    std::atomic<bool> m_stop_requested{false};  ///< set by stop() from any thread
};

}  // namespace

std::unique_ptr<Stage> make_simulated_stage(std::string uri, const SimulatedStageOptions& options) {
    return std::make_unique<SimulatedStage>(std::move(uri), options);
}

std::function<double()> simulated_stage_angle_source(Stage& stage) {
    auto* sim = dynamic_cast<SimulatedStage*>(&stage);
    if (sim == nullptr)
        fail("{}: not a simulated stage (sim://); no physical angle to read", stage.info().uri);
    return [sim] { return sim->physical_angle_deg(); };
}

}  // namespace tirpol::acquisition
