#pragma once
/// \file boson_core_model.h
/// The state of a simulated FLIR Boson core on its own clock, shared by its two links: the control
/// link (BosonSimulator on a pseudo-terminal) and the video (a SimulatedCamera whose frame
/// generator passes through apply()). Thread-safe: both links call it from their own threads.
///
/// Behaviour modelled on the device:
/// - the FPA temperature follows start + drift × t, plus any step a test adds (set_fpa_step_k);
/// - in auto FFC mode an FFC starts by itself when the FPA has moved by the threshold since the
/// last
///   FFC (the SDK's BOSON_SETFFCTEMPTHRESHOLD); in manual mode only on BOSON_RUNFFC;
/// - an FFC closes the shutter for ffc_duration_s (frames show the uniform shutter), then every
///   pixel's offset changes: a frame-wide step (the shutter's temperature estimate) plus a
///   per-pixel residual, both drawn anew per FFC; between FFCs the offset drifts with the FPA
///   temperature;
/// - the frame counter counts at frame_rate_hz from power-up; the last-FFC frame count is the
/// counter
///   when that FFC started.

#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "tirpol/acquisition/internal/boson_fslp.h"

namespace tirpol::acquisition {

struct BosonCoreConfig {
    std::uint32_t serial = 93588;
    std::string part_number =
        "20640A050-6IAAX";  ///< a 640×512 50° Boson part number, ≤ 20 characters
    double frame_rate_hz = 60.0;
    double fpa_start_k = 308.15;
    double fpa_drift_k_per_s = 0.0;
    boson::FfcMode ffc_mode = boson::FfcMode::Auto;  ///< the Boson's factory default
    double ffc_threshold_k = 1.0;
    double ffc_duration_s = 0.5;
    double ffc_step_std_counts = 20.0;  ///< frame-wide offset change per FFC, standard deviation
    double ffc_pixel_std_counts = 2.0;  ///< per-pixel offset change per FFC, standard deviation
    double offset_counts_per_k =
        0.0;  ///< uncorrected offset drift per kelvin of FPA change since the FFC
    double shutter_counts = 7000.0;  ///< what the sensor sees with the shutter closed
    boson::GainMode gain_mode = boson::GainMode::High;
    std::uint64_t seed = 7;
};

class BosonCoreModel {
public:
    using Clock = std::chrono::steady_clock;
    /// Powers up now. Throws tirpol::Error naming the field for a non-positive rate or duration.
    explicit BosonCoreModel(BosonCoreConfig config);

    const BosonCoreConfig& config() const { return m_config; }
    double fpa_temperature_k(Clock::time_point now);
    /// Adds `step_k` to the FPA temperature from now on (a gust of wind, the sun on the housing).
    void add_fpa_step_k(double step_k);
    boson::FfcMode ffc_mode();
    void set_ffc_mode(boson::FfcMode mode);
    double ffc_threshold_k();
    void set_ffc_threshold_k(double threshold_k);
    boson::GainMode gain_mode();
    void set_gain_mode(boson::GainMode mode);
    /// BOSON_RUNFFC: starts an FFC unless one is running.
    void run_ffc(Clock::time_point now);
    boson::FfcStatus ffc_status(Clock::time_point now);
    bool ffc_in_progress(Clock::time_point now);
    std::uint32_t frame_count(Clock::time_point now);
    std::uint32_t last_ffc_frame_count(Clock::time_point now);
    /// FFCs started so far, by RUNFFC and by the core itself (observers, tests).
    int ffcs_started(Clock::time_point now);
    int auto_ffcs_started(Clock::time_point now);
    /// Turns expected scene counts into what the core outputs at `now`: the shutter while an FFC
    /// runs, else scene + the current offsets.
    void apply(std::vector<float>& counts, Clock::time_point now);

private:
    void advance(Clock::time_point now);  ///< with m_mutex held
    void start_ffc(Clock::time_point now, bool automatic);
    double fpa_k(Clock::time_point now) const;
    std::uint32_t frames_at(Clock::time_point now) const;

    BosonCoreConfig m_config;
    std::mutex m_mutex;
    Clock::time_point m_power_up;
    double m_fpa_step_k = 0.0;
    bool m_in_ffc = false;
    Clock::time_point m_ffc_end;
    double m_fpa_at_ffc_k;
    int m_ffcs = 0, m_auto_ffcs = 0, m_completed = 0;
    std::uint32_t m_last_ffc_frame = 0;
    std::vector<float> m_offsets;  ///< per pixel, for the FFC generation m_offsets_generation
    int m_offsets_generation = -1;
};

}  // namespace tirpol::acquisition
