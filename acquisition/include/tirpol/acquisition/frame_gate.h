#pragma once
/// \file frame_gate.h
/// Which frames belong to a capture step (docs/acquisition-cameras.md, "Timing model").
///
/// Every camera back end stamps a frame with its host reception time on CLOCK_REALTIME (Aravis: the
/// stream thread's time at the GVSP leader packet; V4L2: the driver's buffer timestamp mapped to
/// CLOCK_REALTIME; sim://: the instant the frame left the simulated sensor). A host stamp is late
/// by however long the receiving thread waited for the CPU, so when the camera also gives a device
/// timestamp, the gate maps it to host time with the smallest host − device offset seen (the offset
/// plus the shortest latency, allowed to creep by 200 ppm for clock drift) and uses the earlier of
/// the two. Reception marks the *end* of exposure and readout, so a frame received just after the
/// stage settled was mostly exposed before. The gate bounds the exposure start from below by
///     reception − exposure_window,   exposure_window = 1.5 × frame period
/// (one period of integration — a microbolometer integrates continuously over about one frame —
/// plus half a period for readout and transfer latency), and keeps a frame only if that bound is at
/// or after the step's settle end. The frame period is the longer of the camera's nominal one (when
/// it reports a rate) and the shortest interval per frame id observed so far — a camera that cannot
/// keep the rate it reports runs at the longer period; with neither yet, 0.2 s.
///
/// Per-pixel running mean and standard deviation of a frame stream (Welford's online algorithm,
/// B. P. Welford, Technometrics 4(3):419–420, 1962), in double so that 10⁴ frames of 14-bit counts
/// lose nothing. The result is the `counts` / `counts_std` pair of a raw-frame EXR
/// (ARCHITECTURE.md).

#include <cstdint>
#include <optional>
#include <vector>

#include "tirpol/acquisition/camera.h"
#include "tirpol/core/image.h"

namespace tirpol::acquisition {

/// Host CLOCK_REALTIME now, ns since the Unix epoch (the clock of Frame::host_timestamp_ns).
std::int64_t host_realtime_ns();

class FrameGate {
public:
    /// `nominal_frame_rate_hz`: the rate the camera reports, if any.
    explicit FrameGate(std::optional<double> nominal_frame_rate_hz);

    /// How fast the host − device offset estimate may grow: 200 ppm, beyond any camera crystal's
    /// drift.
    static constexpr double kOffsetCreepPerNs = 200e-6;

    /// The ns subtracted from a reception time to bound the exposure start (see file comment).
    std::int64_t exposure_window_ns() const;
    /// Whether `frame` was exposed entirely after `settle_end_ns`; also feeds the rate estimate.
    bool exposed_after(const Frame& frame, std::int64_t settle_end_ns);

    /// Frames received per second of reception time, over runs of consecutive frames (pauses longer
    /// than 2 s, e.g. a software trigger waiting for a move, are left out); dropped frames do not
    /// count. nullopt before two frames.
    std::optional<double> delivered_rate_hz() const;

private:
    /// The frame's reception on the host clock, from its device timestamp where it has one.
    std::int64_t reception_ns(const Frame& frame);

    std::optional<std::int64_t> m_nominal_period_ns;
    std::optional<std::int64_t>
        m_min_offset_ns;  ///< smallest host − device timestamp, drift-corrected
    std::int64_t m_last_device_ns = 0;
    std::optional<std::int64_t> m_min_period_ns;  ///< shortest interval per frame id seen
    bool m_have_last = false;
    std::uint64_t m_last_id = 0;
    std::int64_t m_last_ns = 0;
    std::uint64_t m_intervals = 0;  ///< reception intervals summed into m_span_ns
    std::int64_t m_span_ns = 0;
};

class FrameAverager {
public:
    /// Adds a frame. Throws tirpol::Error if its size differs from the first frame's.
    void add(const Frame& frame);
    std::uint64_t count() const { return m_count; }
    int width() const { return m_width; }
    int height() const { return m_height; }
    /// Mean counts per pixel.
    std::vector<float> mean() const;
    /// Sample standard deviation per pixel (divides by n − 1; 0 for fewer than two frames).
    std::vector<float> stddev() const;
    /// An image with channels `counts` (mean) and `counts_std`, and attribute `frame_count`.
    Image to_image() const;
    void reset();

private:
    int m_width = 0, m_height = 0;
    std::uint64_t m_count = 0;
    std::vector<double> m_mean, m_m2;
};

}  // namespace tirpol::acquisition
