#include "tirpol/acquisition/internal/boson_core_model.h"

#include <cmath>
#include <random>

#include "tirpol/core/error.h"

namespace tirpol::acquisition {

using namespace boson;

BosonCoreModel::BosonCoreModel(BosonCoreConfig config)
    : m_config(std::move(config)), m_power_up(Clock::now()) {
    if (!(m_config.frame_rate_hz > 0.0))
        fail("Boson simulator: frame_rate_hz = {} (expected > 0)", m_config.frame_rate_hz);
    if (!(m_config.ffc_duration_s > 0.0))
        fail("Boson simulator: ffc_duration_s = {} (expected > 0)", m_config.ffc_duration_s);
    if (!(m_config.ffc_threshold_k >= 0.0))
        fail("Boson simulator: ffc_threshold_k = {} (expected ≥ 0)", m_config.ffc_threshold_k);
    if (m_config.part_number.size() > 20)
        fail("Boson simulator: part number '{}' has {} characters (at most 20)",
             m_config.part_number, m_config.part_number.size());
    m_fpa_at_ffc_k = m_config.fpa_start_k;
}

double BosonCoreModel::fpa_k(Clock::time_point now) const {
    const double t_s = std::chrono::duration<double>(now - m_power_up).count();
    return m_config.fpa_start_k + m_config.fpa_drift_k_per_s * t_s + m_fpa_step_k;
}

std::uint32_t BosonCoreModel::frames_at(Clock::time_point now) const {
    const double t_s = std::chrono::duration<double>(now - m_power_up).count();
    return static_cast<std::uint32_t>(std::floor(t_s * m_config.frame_rate_hz));
}

void BosonCoreModel::start_ffc(Clock::time_point now, bool automatic) {
    m_in_ffc = true;
    m_ffc_end = now + std::chrono::duration_cast<Clock::duration>(
                          std::chrono::duration<double>(m_config.ffc_duration_s));
    m_last_ffc_frame = frames_at(now);
    // The FFC measures the shutter now: the drift reference is the FPA temperature at its start.
    m_fpa_at_ffc_k = fpa_k(now);
    ++m_ffcs;
    if (automatic) ++m_auto_ffcs;
}

void BosonCoreModel::advance(Clock::time_point now) {
    if (m_in_ffc && now >= m_ffc_end) {
        m_in_ffc = false;
        ++m_completed;
    }
    if (!m_in_ffc && m_config.ffc_mode == FfcMode::Auto &&
        std::abs(fpa_k(now) - m_fpa_at_ffc_k) >= m_config.ffc_threshold_k)
        start_ffc(now, true);
}

double BosonCoreModel::fpa_temperature_k(Clock::time_point now) {
    const std::lock_guard lock(m_mutex);
    advance(now);
    return fpa_k(now);
}

void BosonCoreModel::add_fpa_step_k(double step_k) {
    const std::lock_guard lock(m_mutex);
    m_fpa_step_k += step_k;
}

FfcMode BosonCoreModel::ffc_mode() {
    const std::lock_guard lock(m_mutex);
    return m_config.ffc_mode;
}

void BosonCoreModel::set_ffc_mode(FfcMode mode) {
    const std::lock_guard lock(m_mutex);
    m_config.ffc_mode = mode;
}

double BosonCoreModel::ffc_threshold_k() {
    const std::lock_guard lock(m_mutex);
    return m_config.ffc_threshold_k;
}

void BosonCoreModel::set_ffc_threshold_k(double threshold_k) {
    const std::lock_guard lock(m_mutex);
    m_config.ffc_threshold_k = threshold_k;
}

GainMode BosonCoreModel::gain_mode() {
    const std::lock_guard lock(m_mutex);
    return m_config.gain_mode;
}

void BosonCoreModel::set_gain_mode(GainMode mode) {
    const std::lock_guard lock(m_mutex);
    m_config.gain_mode = mode;
}

void BosonCoreModel::run_ffc(Clock::time_point now) {
    const std::lock_guard lock(m_mutex);
    advance(now);
    if (!m_in_ffc) start_ffc(now, false);
}

FfcStatus BosonCoreModel::ffc_status(Clock::time_point now) {
    const std::lock_guard lock(m_mutex);
    advance(now);
    if (m_in_ffc) return FfcStatus::InProgress;
    return m_completed > 0 ? FfcStatus::Complete : FfcStatus::NoFfcPerformed;
}

bool BosonCoreModel::ffc_in_progress(Clock::time_point now) {
    const std::lock_guard lock(m_mutex);
    advance(now);
    return m_in_ffc;
}

std::uint32_t BosonCoreModel::frame_count(Clock::time_point now) {
    const std::lock_guard lock(m_mutex);
    advance(now);
    return frames_at(now);
}

std::uint32_t BosonCoreModel::last_ffc_frame_count(Clock::time_point now) {
    const std::lock_guard lock(m_mutex);
    advance(now);
    return m_last_ffc_frame;
}

int BosonCoreModel::ffcs_started(Clock::time_point now) {
    const std::lock_guard lock(m_mutex);
    advance(now);
    return m_ffcs;
}

int BosonCoreModel::auto_ffcs_started(Clock::time_point now) {
    const std::lock_guard lock(m_mutex);
    advance(now);
    return m_auto_ffcs;
}

void BosonCoreModel::apply(std::vector<float>& counts, Clock::time_point now) {
    const std::lock_guard lock(m_mutex);
    advance(now);
    if (m_in_ffc) {
        std::fill(counts.begin(), counts.end(), static_cast<float>(m_config.shutter_counts));
        return;
    }
    if (m_offsets_generation != m_completed || m_offsets.size() != counts.size()) {
        // Reproducible per FFC: the same seed and FFC number give the same offsets.
        std::mt19937_64 rng(m_config.seed * 1000003u + static_cast<std::uint64_t>(m_completed));
        std::normal_distribution<double> step(0.0, m_config.ffc_step_std_counts);
        std::normal_distribution<double> pixel(0.0, m_config.ffc_pixel_std_counts);
        const double frame_step = m_config.ffc_step_std_counts > 0.0 ? step(rng) : 0.0;
        m_offsets.resize(counts.size());
        for (float& o : m_offsets)
            o = static_cast<float>(frame_step +
                                   (m_config.ffc_pixel_std_counts > 0.0 ? pixel(rng) : 0.0));
        m_offsets_generation = m_completed;
    }
    const double drift = m_config.offset_counts_per_k * (fpa_k(now) - m_fpa_at_ffc_k);
    for (std::size_t i = 0; i < counts.size(); ++i)
        counts[i] += m_offsets[i] + static_cast<float>(drift);
}

}  // namespace tirpol::acquisition
