#pragma once
// An in-process rig for the live-view tests: a simulated stage that turns at a finite speed and a
// free-running simulated camera looking, through the polarizer on that stage, at a source of known
// linear Stokes vector. Counts follow Malus's law for an ideal analyzer at the stage's physical
// angle at the end of each exposure: I(θ) = ½·(S0 + S1·cos 2θ + S2·sin 2θ) (Chipman, Lam & Young
// 2018, eq 6.35), so frames exposed during a move carry the wrong angle's counts, as on a real rig.

#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <thread>

#include "polarizer_cycle.h"
#include "tirpol/acquisition/internal/sim_stage.h"
#include "tirpol/acquisition/sim/simulated_camera.h"

namespace tirpol::test {

struct PolarizedSource {
    double s0 = 4000.0, dolp = 0.3, aop_deg = 30.0;
    double s1() const { return s0 * dolp * std::cos(2.0 * aop_deg * std::numbers::pi / 180.0); }
    double s2() const { return s0 * dolp * std::sin(2.0 * aop_deg * std::numbers::pi / 180.0); }
};

struct SimRig {
    std::unique_ptr<acquisition::Stage> stage;
    std::unique_ptr<acquisition::SimulatedCamera> camera;

    SimRig(const PolarizedSource& source, double deg_per_s, double fps = 100.0) {
        acquisition::SimulatedStageOptions stage_options;
        stage_options.deg_per_s = deg_per_s;
        stage = acquisition::make_simulated_stage("sim://", stage_options);
        acquisition::SimulatedCameraConfig config;
        config.width = 16;
        config.height = 12;
        config.frame_rate_hz = fps;
        config.buffers = 64;
        config.noise_std_counts = 2.0;
        config.fpa_temperature_k = 303.0;
        camera = std::make_unique<acquisition::SimulatedCamera>(
            config,
            [source](double angle_deg, std::vector<float>& counts) {
                const double t = 2.0 * angle_deg * std::numbers::pi / 180.0;
                const double i =
                    0.5 * (source.s0 + source.s1() * std::cos(t) + source.s2() * std::sin(t));
                std::fill(counts.begin(), counts.end(), static_cast<float>(i));
            },
            acquisition::simulated_stage_angle_source(*stage));
    }
};

/// The rig with the live view's grab thread and polarizer cycle running on it (counts, no
/// calibration).
struct CyclingRig {
    SimRig rig;
    live::FrameFeed feed;
    live::DisplayConverter converter;
    live::PolarizerCycle cycle;

    CyclingRig(const PolarizedSource& source, double deg_per_s, int frames_per_angle,
               double settle_s)
        : rig(source, deg_per_s),
          feed(*rig.camera),
          converter(rig.camera->info(), nullptr, live::DisplayUnit::Counts),
          cycle(feed, *rig.stage, converter, options(frames_per_angle, settle_s)) {
        if (!feed.start().ok()) throw std::runtime_error("the simulated camera did not start");
        cycle.start();
    }
    ~CyclingRig() {
        cycle.stop();
        feed.stop();
    }
    static live::CycleOptions options(int frames_per_angle, double settle_s) {
        live::CycleOptions o;
        o.frames_per_angle = frames_per_angle;
        o.settle_s = settle_s;
        return o;
    }
};

/// Polls `condition` every 20 ms until it holds (true) or `timeout` passes (false).
inline bool wait_until(const std::function<bool()>& condition, std::chrono::seconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (!condition()) {
        if (std::chrono::steady_clock::now() > deadline) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return true;
}

}  // namespace tirpol::test
