#include "tirpol/acquisition/internal/frame_id.h"

namespace tirpol::acquisition {

FrameIdUnwrapper::FrameIdUnwrapper(std::uint64_t modulus, bool zero_skipped)
    : m_cycle(zero_skipped ? modulus - 1 : modulus), m_zero_skipped(zero_skipped) {}

std::uint64_t FrameIdUnwrapper::index_of(std::uint64_t raw_id) const {
    const std::uint64_t index = m_zero_skipped ? raw_id - 1 : raw_id;
    return index % m_cycle;
}

FrameIdStep FrameIdUnwrapper::next(std::uint64_t raw_id) {
    const std::uint64_t index = index_of(raw_id);
    FrameIdStep step;
    if (!m_started) {
        m_started = true;
        m_last_index = index;
        m_last_id = raw_id;
        step.id = m_last_id;
        return step;
    }
    const std::uint64_t distance = (index + m_cycle - m_last_index) % m_cycle;
    m_last_index = index;
    if (distance == 0) {
        step.id = m_last_id;
        step.duplicate = true;
        return step;
    }
    if (distance > m_cycle / 2) {
        step.reset = true;
        m_last_id += 1;
    } else {
        step.missed = distance - 1;
        m_last_id += distance;
    }
    step.id = m_last_id;
    return step;
}

}  // namespace tirpol::acquisition
