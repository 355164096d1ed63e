#pragma once
// Writes session records on a thread of its own, so that compressing and fsyncing an EXR never
// stalls grabbing (a camera's buffer queue overflows while the grabbing thread writes).

#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "tirpol/core/session.h"

namespace tirpol::acquisition::detail {

class RecordWriter {
public:
    /// At most `max_pending` records wait in memory; submit() blocks beyond that.
    RecordWriter(SessionWriter& session, std::size_t max_pending = 2);
    /// Writes what is queued (nothing taken is lost on an error path), then stops.
    ~RecordWriter();
    RecordWriter(const RecordWriter&) = delete;
    RecordWriter& operator=(const RecordWriter&) = delete;

    /// Queues a record (and the camera's delivered frame rate so far, written with it); rethrows
    /// (once) an error of an earlier write.
    void submit(SessionRecord record, Image frame,
                std::optional<double> camera_frame_rate_hz = std::nullopt);
    /// Waits until every queued record is written; rethrows a write error.
    void flush();
    /// Records in the session, written or queued: for messages while writes are in flight.
    std::size_t records() const;
    /// The file of the record whose write failed (empty while none has): the write runs behind the
    /// capture, so the step being captured when the error surfaces is usually a later one.
    std::string failed_file() const;

private:
    void run();
    void rethrow_locked(std::unique_lock<std::mutex>& lock);

    SessionWriter& m_session;
    const std::size_t m_max_pending;
    mutable std::mutex m_mutex;
    std::condition_variable m_changed;
    struct Item {
        SessionRecord record;
        Image frame;
        std::optional<double> camera_frame_rate_hz;
    };
    std::deque<Item> m_queue;
    bool m_busy = false, m_stop = false;
    std::size_t m_written;
    std::exception_ptr m_error;
    std::string m_failed_file;
    std::thread m_thread;
};

}  // namespace tirpol::acquisition::detail
