#include "tirpol/acquisition/sim_stage.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <thread>

#include "move_preconditions.h"
#include "tirpol/acquisition/angles.h"
#include "tirpol/core/error.h"

namespace tirpol::acquisition {

namespace {

class SimulatedStage final : public Stage {
public:
    SimulatedStage(std::string uri, SimulatedStageOptions options)
        : m_options(options), m_from_deg(wrap_degrees(options.start_angle_deg)), m_to_deg(m_from_deg) {
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
        return wrap_degrees(std::round(physical_angle_deg() * m_options.counts_per_degree) / m_options.counts_per_degree);
    }

    /// Where the mount is now, moving at deg_per_s between the start and end of a move; any thread.
    double physical_angle_deg() const {
        std::lock_guard lock(m_mutex);
        const auto now = Clock::now();
        if (now >= m_move_end) return wrap_degrees(m_to_deg);
        const double f = std::chrono::duration<double>(now - m_move_start) / std::chrono::duration<double>(m_move_end - m_move_start);
        return wrap_degrees(m_from_deg + (m_to_deg - m_from_deg) * std::clamp(f, 0.0, 1.0));
    }

private:
    using Clock = std::chrono::steady_clock;

    Status travel(double target_deg, std::chrono::milliseconds timeout) {
        const double from_deg = physical_angle_deg();
        if (m_options.deg_per_s > 0.0) {
            const double seconds = std::abs(target_deg - from_deg) / m_options.deg_per_s;
            const auto needed = std::chrono::duration<double>(seconds);
            if (needed > timeout) {
                std::this_thread::sleep_for(timeout);
                return DeviceError{DeviceErrorCode::Timeout, fmt::format("{}: move needs {:.2f} s, timeout {} ms", m_info.uri, seconds, timeout.count())};
            }
            {
                std::lock_guard lock(m_mutex);
                m_from_deg = from_deg;
                m_to_deg = target_deg;
                m_move_start = Clock::now();
                m_move_end = m_move_start + std::chrono::duration_cast<Clock::duration>(needed);
            }
            std::this_thread::sleep_until(m_move_end);
        }
        std::lock_guard lock(m_mutex);
        m_from_deg = m_to_deg = target_deg;
        m_move_end = Clock::now();
        return ok_status();
    }

    SimulatedStageOptions m_options;
    StageInfo m_info;
    mutable std::mutex m_mutex;  ///< the trajectory is read by simulated cameras on their own threads
    double m_from_deg, m_to_deg;
    Clock::time_point m_move_start{}, m_move_end{};
    bool m_homed = false;
    int m_moves = 0;
};

}  // namespace

std::unique_ptr<Stage> make_simulated_stage(std::string uri, const SimulatedStageOptions& options) {
    return std::make_unique<SimulatedStage>(std::move(uri), options);
}

std::function<double()> simulated_stage_angle_source(Stage& stage) {
    auto* sim = dynamic_cast<SimulatedStage*>(&stage);
    if (sim == nullptr) fail("{}: not a simulated stage (sim://); no physical angle to read", stage.info().uri);
    return [sim] { return sim->physical_angle_deg(); };
}

}  // namespace tirpol::acquisition
