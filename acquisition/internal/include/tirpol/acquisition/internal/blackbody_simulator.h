#pragma once
/// \file blackbody_simulator.h
/// A Fluke 4180-style blackbody controller that speaks the real serial protocol (fluke_scpi.h) on a
/// pseudo-terminal (`tirpol-blackbody-sim`, or a thread in tests) or in-process (`sim://`). Its
/// plate follows a first-order thermal response, T(t) = T_set + (T_0 − T_set)·exp(−(t − t_0)/τ),
/// from the temperature it had when the set-point changed; the control sensor reads it with
/// Gaussian noise, sampled every sample_period_s on the device's own clock. The stability flag
/// (SOUR:STAB:TEST?) is computed as the controller's STABLE LIMIT test: 1 when every control
/// reading of the last stability_window_s lies within ± SOUR:STAB:LIM of their mean (a full window
/// is needed). Faults on request from the N-th set-point on: the over-temperature cutout trips
/// (heater off: the plate cools to ambient, SOUR:PROT:TRIP? answers 1), no reply at all, or garbled
/// replies.

#include <chrono>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "tirpol/acquisition/internal/fluke_scpi.h"
#include "tirpol/acquisition/sim/stage_simulator.h"

namespace tirpol::acquisition {

enum class BlackbodyFault { None, OverTemperature, NoReply, Garbled };
/// "none" | "over-temperature" | "no-reply" | "garbled".
std::optional<BlackbodyFault> parse_blackbody_fault(const std::string& text);

struct BlackbodySimulatorOptions {
    std::string model = "4180";
    double ambient_k = 296.15;        ///< where the plate starts, and cools to after a cutout
    double time_constant_s = 60.0;    ///< τ of the first-order response (a 4180 plate: minutes)
    double noise_k = 0.005;           ///< control-sensor noise, standard deviation
    double stability_limit_k = 0.05;  ///< SOUR:STAB:LIM at power-up
    double stability_window_s = 30.0;
    double sample_period_s = 0.25;
    BlackbodyFault fault = BlackbodyFault::None;
    int fault_on_set = 1;  ///< the 1-based set-point command from which the fault starts
    std::uint64_t seed = 1;
};

class BlackbodySimulator final : public PtyDevice {
public:
    /// Throws tirpol::Error for a model other than 4180/4181 or a non-positive τ, window or period.
    explicit BlackbodySimulator(BlackbodySimulatorOptions options,
                                Clock::time_point start = Clock::now());

    std::vector<std::uint8_t> receive(std::span<const std::uint8_t> bytes,
                                      Clock::time_point now) override;
    std::vector<std::uint8_t> poll(Clock::time_point now) override;

    /// The plate's true (noise-free) temperature at `now`, what a camera sees; safe from any
    /// thread.
    double plate_temperature_k(Clock::time_point now) const;

private:
    std::string execute(const std::string& line, Clock::time_point now);
    void sample_until(Clock::time_point now);
    bool stable() const;
    void set_target_k(double target_k, Clock::time_point now);

    BlackbodySimulatorOptions m_options;
    double m_min_c, m_max_c;
    std::vector<std::uint8_t> m_rx;
    std::mt19937_64 m_rng;
    double m_limit_k;
    double m_set_point_k;
    bool m_tripped = false, m_silent = false, m_garbled = false;
    int m_sets = 0;
    std::deque<std::string> m_errors;
    struct Sample {
        Clock::time_point at;
        double reading_k;
    };
    std::deque<Sample> m_samples;
    Clock::time_point m_next_sample;

    /// The trajectory, read by other threads (plate_temperature_k).
    mutable std::mutex m_mutex;
    double m_from_k, m_target_k;
    Clock::time_point m_since;
};

}  // namespace tirpol::acquisition
