#pragma once
/// \file latest_slot.h
/// A single-slot "latest value" buffer between a producer that must never wait (the camera's grab
/// thread) and consumers that take what they can at their own pace (each browser's display loop).
/// Publishing replaces the value; a consumer that was slow simply never sees the values in between:
/// display frames are dropped, camera frames never are.

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>

namespace tirpol::live {

template <typename T>
class LatestSlot {
public:
    struct Snapshot {
        std::uint64_t sequence = 0;  ///< 0: nothing published yet; +1 per publish
        std::shared_ptr<const T> value;
    };

    /// Replaces the value (never blocks on a consumer: the lock only guards a pointer swap).
    void publish(std::shared_ptr<const T> value) {
        {
            std::lock_guard lock(m_mutex);
            m_latest.value = std::move(value);
            ++m_latest.sequence;
        }
        m_published.notify_all();
    }

    Snapshot latest() const {
        std::lock_guard lock(m_mutex);
        return m_latest;
    }

    /// The latest value once its sequence is above `after`, waiting at most `timeout`; the snapshot
    /// returned may still be at or below `after` when the wait timed out.
    Snapshot wait_newer(std::uint64_t after, std::chrono::milliseconds timeout) const {
        std::unique_lock lock(m_mutex);
        m_published.wait_for(lock, timeout, [&] { return m_latest.sequence > after; });
        return m_latest;
    }

private:
    mutable std::mutex m_mutex;
    mutable std::condition_variable m_published;
    Snapshot m_latest;
};

}  // namespace tirpol::live
