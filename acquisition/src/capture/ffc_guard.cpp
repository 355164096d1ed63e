#include "capture/ffc_guard.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "tirpol/acquisition/frame_gate.h"

namespace tirpol::acquisition::detail {

namespace {
long angle_key(double angle_deg) {
    const double wrapped = std::fmod(std::fmod(angle_deg, 180.0) + 180.0, 180.0);
    return std::lround(wrapped * 1000.0) % 180000;
}
}  // namespace

FfcGuard::FfcGuard(const FfcOptions& options) : m_options(options) {}

FfcEvent FfcGuard::event(FfcEvent::Kind kind, int repeat, std::string reason) {
    FfcEvent e;
    e.kind = kind;
    e.host_timestamp_ns = host_realtime_ns();
    e.repeat = repeat;
    e.reason = std::move(reason);
    return e;
}

FfcEvent FfcGuard::detected(int repeat, std::string reason) {
    return event(FfcEvent::Kind::Detected, repeat, std::move(reason));
}

Result<std::optional<FfcEvent>> FfcGuard::before_cycle(int repeat, int cycles_started, bool retry) {
    m_cycle_means.clear();
    FfcControl* link = m_options.control;
    if (!link) return std::optional<FfcEvent>{};
    if (!m_manual_set) {
        if (auto s = link->set_manual_ffc(); !s) return s.error();
        m_manual_set = true;
    }
    auto fpa = link->fpa_temperature_k();
    if (!fpa) return fpa.error();
    std::optional<std::string> reason;
    if (retry) {
        reason = "before taking again a cycle an FFC fell in";
    } else {
        switch (m_options.schedule) {
            case FfcOptions::Schedule::EveryCycle:
                reason = "every cycle";
                break;
            case FfcOptions::Schedule::EveryN:
                if (cycles_started % std::max(1, m_options.every_n_cycles) == 0)
                    reason = fmt::format("every {} cycles", m_options.every_n_cycles);
                break;
            case FfcOptions::Schedule::FpaDelta:
                if (!m_fpa_at_last_ffc_k) {
                    reason = "first cycle";
                } else if (std::abs(fpa.value() - *m_fpa_at_last_ffc_k) > m_options.fpa_delta_k) {
                    reason = fmt::format("FPA moved {:+.2f} K since the last FFC (threshold {} K)",
                                         fpa.value() - *m_fpa_at_last_ffc_k, m_options.fpa_delta_k);
                }
                break;
        }
    }
    std::optional<FfcEvent> ran;
    if (reason) {
        FfcEvent e = event(FfcEvent::Kind::Scheduled, repeat, *reason);
        e.fpa_temperature_k = fpa.value();
        if (auto s = link->run_ffc_and_wait(); !s) return s.error();
        auto frame = link->last_ffc_marker();
        if (!frame) return frame.error();
        e.device_frame_count = static_cast<std::int64_t>(frame.value());
        m_fpa_at_last_ffc_k = fpa.value();
        ran = std::move(e);
    }
    auto marker = link->last_ffc_marker();
    if (!marker) return marker.error();
    m_marker_at_cycle_start = marker.value();
    return ran;
}

void FfcGuard::begin_step() {
    m_step_sum = 0.0;
    m_step_frames = 0;
}

std::optional<std::string> FfcGuard::observe(const Frame& frame) {
    // With a link the core says when it corrected; frame statistics would only add false alarms (a
    // scene that changes).
    if (m_options.control) {
        // A core that reports its FFC state in each frame (a Lepton's telemetry) says so directly.
        if (frame.telemetry && frame.telemetry->ffc_state == 2)
            return fmt::format(
                "frame {}: the core's telemetry says an FFC is in progress (core "
                "frame {})",
                frame.frame_id, frame.telemetry->device_frame_counter);
        return std::nullopt;
    }
    double sum = 0.0;
    for (float c : frame.counts) sum += c;
    const double mean = frame.counts.empty() ? 0.0 : sum / static_cast<double>(frame.counts.size());
    if (m_step_frames > 0) {
        const double step_mean = m_step_sum / m_step_frames;
        if (std::abs(mean - step_mean) > m_options.frame_step_counts)
            return fmt::format(
                "frame {} mean stepped by {:+.1f} counts from its step's first {} frames "
                "(threshold {})",
                frame.frame_id, mean - step_mean, m_step_frames, m_options.frame_step_counts);
    }
    m_step_sum += mean;
    ++m_step_frames;
    return std::nullopt;
}

void FfcGuard::end_step(double angle_deg) {
    if (m_step_frames > 0) m_cycle_means[angle_key(angle_deg)] = m_step_sum / m_step_frames;
}

void FfcGuard::abandon_cycle() { m_cycle_means.clear(); }

Result<std::optional<FfcEvent>> FfcGuard::end_cycle(int repeat) {
    if (FfcControl* link = m_options.control) {
        auto marker = link->last_ffc_marker();
        if (!marker) return marker.error();
        if (m_marker_at_cycle_start && marker.value() != *m_marker_at_cycle_start) {
            FfcEvent e = detected(
                repeat,
                fmt::format("the core's last-FFC frame count moved from {} to {} during the cycle",
                            *m_marker_at_cycle_start, marker.value()));
            e.device_frame_count = static_cast<std::int64_t>(marker.value());
            if (auto fpa = link->fpa_temperature_k()) e.fpa_temperature_k = fpa.value();
            return std::optional<FfcEvent>(std::move(e));
        }
        return std::optional<FfcEvent>{};
    }
    // Any linear analyzer passes a + b cos 2θ + c sin 2θ: I0 + I90 = I45 + I135 = 2a.
    const long k0 = angle_key(0), k45 = angle_key(45), k90 = angle_key(90), k135 = angle_key(135);
    if (m_cycle_means.size() == 4 && m_cycle_means.count(k0) && m_cycle_means.count(k45) &&
        m_cycle_means.count(k90) && m_cycle_means.count(k135)) {
        const double closure =
            m_cycle_means[k0] + m_cycle_means[k90] - m_cycle_means[k45] - m_cycle_means[k135];
        if (std::abs(closure) > m_options.cycle_step_counts)
            return std::optional<FfcEvent>(detected(
                repeat,
                fmt::format("cycle closure I0 + I90 − I45 − I135 = {:+.1f} counts (threshold {})",
                            closure, m_options.cycle_step_counts)));
    }
    // A still scene changes every angle's mean by the same amount from one cycle to the next (an
    // FFC between cycles included); an offset step inside the cycle changes only the angles after
    // it.
    if (!m_reference_means.empty() && m_reference_means.size() == m_cycle_means.size()) {
        double lo = 0.0, hi = 0.0;
        bool first = true, same_angles = true;
        for (const auto& [key, mean] : m_cycle_means) {
            const auto ref = m_reference_means.find(key);
            if (ref == m_reference_means.end()) {
                same_angles = false;
                break;
            }
            const double change = mean - ref->second;
            lo = first ? change : std::min(lo, change);
            hi = first ? change : std::max(hi, change);
            first = false;
        }
        if (same_angles && hi - lo > m_options.cycle_step_counts)
            return std::optional<FfcEvent>(
                detected(repeat, fmt::format("the angles' means changed unequally from the last "
                                             "accepted cycle (spread {:.1f} "
                                             "counts, threshold {})",
                                             hi - lo, m_options.cycle_step_counts)));
    }
    m_reference_means = m_cycle_means;
    return std::optional<FfcEvent>{};
}

}  // namespace tirpol::acquisition::detail
