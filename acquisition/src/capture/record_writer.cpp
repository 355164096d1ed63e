#include "capture/record_writer.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace tirpol::acquisition::detail {

RecordWriter::RecordWriter(SessionWriter& session, std::size_t max_pending)
    : m_session(session),
      m_max_pending(max_pending),
      m_written(session.manifest().records.size()),
      m_thread([this] { run(); }) {}

RecordWriter::~RecordWriter() {
    {
        std::lock_guard lock(m_mutex);
        m_stop = true;
    }
    m_changed.notify_all();
    m_thread.join();
}

void RecordWriter::rethrow_locked(std::unique_lock<std::mutex>&) {
    if (m_error) std::rethrow_exception(std::exchange(m_error, nullptr));
}

void RecordWriter::submit(SessionRecord record, Image frame,
                          std::optional<double> camera_frame_rate_hz) {
    std::unique_lock lock(m_mutex);
    m_changed.wait(lock, [this] { return m_queue.size() < m_max_pending || m_error; });
    rethrow_locked(lock);
    m_queue.push_back({std::move(record), std::move(frame), camera_frame_rate_hz});
    m_changed.notify_all();
}

void RecordWriter::flush() {
    std::unique_lock lock(m_mutex);
    m_changed.wait(lock, [this] { return (m_queue.empty() && !m_busy) || m_error; });
    rethrow_locked(lock);
}

std::string RecordWriter::failed_file() const {
    std::lock_guard lock(m_mutex);
    return m_failed_file;
}

std::size_t RecordWriter::records() const {
    std::lock_guard lock(m_mutex);
    return m_written + m_queue.size() + (m_busy ? 1 : 0);
}

void RecordWriter::run() {
    // Compressing an EXR may wait; grabbing may not: on a busy machine the scheduler should favour
    // the grabbing thread (and a camera served in-process). Best effort: a refusal changes nothing
    // else.
    (void)::setpriority(PRIO_PROCESS, static_cast<id_t>(::syscall(SYS_gettid)), 10);
    std::unique_lock lock(m_mutex);
    for (;;) {
        m_changed.wait(lock, [this] { return !m_queue.empty() || m_stop; });
        if (m_queue.empty()) return;  // stopping, everything written
        if (m_error) {  // a failed write (full disk) fails the rest too: drop them, the error says
                        // so
            m_queue.clear();
            m_changed.notify_all();
            continue;
        }
        auto item = std::move(m_queue.front());
        m_queue.pop_front();
        m_busy = true;
        lock.unlock();
        std::exception_ptr error;
        try {
            if (item.camera_frame_rate_hz)
                m_session.set_camera_frame_rate(*item.camera_frame_rate_hz);
            m_session.add_record(item.record, item.frame);
        } catch (...) {
            error = std::current_exception();
        }
        lock.lock();
        m_busy = false;
        if (error) {
            m_error = error;
            m_failed_file = item.record.file;
        } else
            ++m_written;
        m_changed.notify_all();
    }
}

}  // namespace tirpol::acquisition::detail
