#pragma once
/// \file frame_id.h
/// Turns a device's wrapping frame counter into a monotonic 64-bit frame id and counts the frames
/// that never arrived (gaps). Two counters matter:
/// - GigE Vision GVSP block ids (GigE Vision 1.x, 16-bit): 1, 2, …, 65535, 1, … — 0 is reserved
///   ("frame id is a 16 bit value, 0 is invalid", Aravis src/arvfakecamera.c), so 65535 → 1 is one
///   step.
/// - V4L2 `v4l2_buffer.sequence` (32-bit, starts at 0 and wraps 2^32−1 → 0; kernel docs, "struct
/// v4l2_buffer").

#include <cstdint>

namespace tirpol::acquisition {

/// What one received raw id means.
struct FrameIdStep {
    std::uint64_t id = 0;      ///< monotonic id: the first raw id seen, then + steps
    std::uint64_t missed = 0;  ///< ids skipped since the previous frame (frames lost)
    bool duplicate = false;    ///< the same raw id as the previous frame (not a new frame)
    bool reset =
        false;  ///< the counter jumped backwards by more than half its range (device restart)
};

/// Unwraps a counter that counts modulo `modulus`, optionally skipping 0 on wrap.
/// A forward distance larger than half the counter's range is read as a counter reset, not as a
/// huge loss: the id then advances by one and `reset` is set.
class FrameIdUnwrapper {
public:
    /// `modulus`: number of raw values the counter takes before wrapping (65536 for GVSP, 2^32 for
    /// V4L2); `zero_skipped`: the counter never shows 0 (GVSP), so it cycles through modulus − 1
    /// values.
    FrameIdUnwrapper(std::uint64_t modulus, bool zero_skipped);

    static FrameIdUnwrapper gige_vision_16bit() { return {65536, true}; }
    static FrameIdUnwrapper v4l2_sequence() { return {std::uint64_t{1} << 32, false}; }

    /// Feeds the next raw id (in arrival order).
    FrameIdStep next(std::uint64_t raw_id);
    /// Forgets the history (e.g. after a stream restart).
    void restart() { m_started = false; }

private:
    std::uint64_t index_of(std::uint64_t raw_id) const;

    std::uint64_t m_cycle;  ///< number of distinct raw values
    bool m_zero_skipped;
    bool m_started = false;
    std::uint64_t m_last_index = 0;
    std::uint64_t m_last_id = 0;
};

}  // namespace tirpol::acquisition
