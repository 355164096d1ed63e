// couple_simulated_polarizer (capture.h): the angle a simulated camera's polarizer is at, taken
// from the stage that turns it.

#include <atomic>
#include <mutex>

#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/internal/angles.h"
#include "tirpol/acquisition/internal/sim_stage.h"
#include "tirpol/acquisition/sim/simulated_camera.h"

namespace tirpol::acquisition {

namespace {

/// What the camera's thread reads: the stage's physical angle while the stage lives (sim://), else
/// the last angle its driver reached. Shared, so the camera may outlive the stage.
struct PolarizerAngle {
    std::mutex mutex;
    std::function<double()> physical;  ///< guarded by mutex; cleared when the stage goes
    std::atomic<double> last_known_deg{0.0};

    double now() {
        std::lock_guard lock(mutex);
        return physical ? physical() : last_known_deg.load();
    }
};

/// Forwards every call to the stage it owns and records where it ends up.
class AngleTrackingStage final : public Stage {
public:
    AngleTrackingStage(std::unique_ptr<Stage> stage, std::shared_ptr<PolarizerAngle> angle)
        : m_stage(std::move(stage)), m_angle(std::move(angle)) {}
    ~AngleTrackingStage() override {
        std::lock_guard lock(m_angle->mutex);
        m_angle->physical = nullptr;
    }
    AngleTrackingStage(const AngleTrackingStage&) = delete;
    AngleTrackingStage& operator=(const AngleTrackingStage&) = delete;

    StageInfo info() const override { return m_stage->info(); }
    bool is_homed() const override { return m_stage->is_homed(); }
    Status home(std::chrono::milliseconds timeout) override {
        Status s = m_stage->home(timeout);
        if (s) m_angle->last_known_deg = 0.0;
        return s;
    }
    Status move_absolute(double angle_deg, std::chrono::milliseconds timeout) override {
        Status s = m_stage->move_absolute(angle_deg, timeout);
        if (s) m_angle->last_known_deg = wrap_degrees(angle_deg);
        return s;
    }
    Result<double> position_deg() override {
        Result<double> r = m_stage->position_deg();
        if (r) m_angle->last_known_deg = r.value();
        return r;
    }
    Status stop() override { return m_stage->stop(); }
    Result<bool> home_sensor_active() override { return m_stage->home_sensor_active(); }

private:
    std::unique_ptr<Stage> m_stage;
    std::shared_ptr<PolarizerAngle> m_angle;
};

}  // namespace

std::unique_ptr<Stage> couple_simulated_polarizer(Camera& camera, std::unique_ptr<Stage> stage) {
    auto* simulated = dynamic_cast<SimulatedCamera*>(&camera);
    if (simulated == nullptr || simulated->has_angle_source() || !stage) return stage;
    auto angle = std::make_shared<PolarizerAngle>();
    try {
        angle->physical = simulated_stage_angle_source(*stage);
    } catch (const Error&) {  // a driver stage: no physical angle, only what its driver knows
    }
    auto tracking = std::make_unique<AngleTrackingStage>(std::move(stage), angle);
    simulated->set_angle_source([angle] { return angle->now(); });
    return tracking;
}

}  // namespace tirpol::acquisition
