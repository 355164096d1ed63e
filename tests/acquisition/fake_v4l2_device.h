#pragma once
// FakeV4l2Device: a V4l2Io that behaves like a UVC capture device (uvcvideo) as the kernel's V4L2
// API documentation specifies it, for testing the v4l2:// backend without a kernel device:
// - VIDIOC_QUERYCAP, G/S_FMT (discrete formats; unsupported ones either adjusted like current
// drivers
//   or refused with EINVAL like older ones; EBUSY while buffers are allocated), G/S_PARM;
// - VIDIOC_REQBUFS (MMAP only; the driver may grant fewer buffers; count 0 frees; EBUSY while
//   streaming or while buffers are still mapped), VIDIOC_QUERYBUF, mmap/munmap by offset;
// - VIDIOC_QBUF (EINVAL for a bad index or a buffer already queued), VIDIOC_DQBUF (EAGAIN on a
//   non-blocking fd with nothing done, EINVAL when not streaming), STREAMON (EINVAL without
//   buffers), STREAMOFF (returns every buffer to the application);
// - poll(): POLLERR when not streaming (V4L2 "poll()" page), POLLIN when a buffer is done. Time is
//   virtual: a poll that would wait lets the sensor produce one frame; with no buffer queued that
//   frame is lost but still advances `sequence` (uvcvideo counts frames, not buffers).
// Scripted faults: sequence gaps, corrupted (V4L2_BUF_FLAG_ERROR) or short frames, a spurious
// wake-up (EAGAIN after POLLIN), a stalled sensor (poll times out), unplugging (ENODEV, POLLERR).

#include <fcntl.h>
#include <linux/videodev2.h>
#include <sys/mman.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <ctime>
#include <deque>
#include <functional>
#include <string>
#include <vector>

#include "tirpol/acquisition/internal/v4l2_camera.h"

namespace tirpol::test {

class FakeV4l2Device final : public acquisition::V4l2Io {
public:
    struct Format {
        std::uint32_t fourcc;
        std::uint32_t width, height;
    };

    explicit FakeV4l2Device(std::string path = "/dev/video0") : m_path(std::move(path)) {}

    // --- configuration and scripted faults ---
    std::vector<Format> formats = {{V4L2_PIX_FMT_Y16, 160, 120}, {V4L2_PIX_FMT_GREY, 160, 120}};
    std::vector<std::uint32_t> frame_rates_hz = {9, 30, 60};
    bool refuse_unsupported_with_einval = false;
    std::uint32_t max_buffers = 8;
    std::uint32_t next_sequence = 0;
    long frames_left = -1;        ///< frames the sensor will still produce (−1: unlimited)
    std::uint32_t skip_next = 0;  ///< frames the sensor loses before the next one (sequence gap)
    bool corrupt_next = false;    ///< next frame carries V4L2_BUF_FLAG_ERROR
    bool short_next = false;      ///< next frame has half its bytes
    bool spurious_wakeup_next = false;
    bool unplugged = false;
    /// Stamp buffers with CLOCK_MONOTONIC at the instant they are filled, as uvcvideo does
    /// (default: a synthetic clock, sequence × period, that tests of ids and timestamps compare
    /// exactly).
    bool stamp_with_monotonic_clock = false;
    /// When set, writes a Y16 frame's width × height words instead of the test pattern (called once
    /// per frame the sensor delivers into a buffer, with its sequence number): a core whose frames
    /// carry more than a ramp, e.g. a Lepton's telemetry rows.
    std::function<void(std::uint32_t sequence, std::vector<std::uint16_t>& words)> fill_frame;

    /// The sensor delivers a frame now into the next queued buffer (or loses it if none is queued),
    /// whether or not anyone polls: a free-running camera during a stage move.
    void expose_frame_now() { produce_frame(); }

    // --- state, for assertions ---
    std::size_t allocated_count() const { return m_buffers.size(); }
    std::size_t mapped_count() const {
        std::size_t n = 0;
        for (const auto& b : m_buffers) n += b.mapped ? 1 : 0;
        return n;
    }
    std::size_t queued_count() const { return m_incoming.size() + m_done.size(); }
    bool streaming() const { return m_streaming; }
    bool is_open() const { return m_open; }
    bool opened_nonblocking() const { return m_nonblocking; }
    std::uint32_t period_us() const { return 1000000u / m_rate_hz; }

    /// The test pattern of frame `sequence` at (x, y): Y16 (x + 2y + 7 seq) mod 2^16, GREY (x + y +
    /// seq) mod 2^8.
    static std::uint32_t pattern(std::uint32_t fourcc, std::uint32_t x, std::uint32_t y,
                                 std::uint32_t sequence) {
        return fourcc == V4L2_PIX_FMT_Y16 ? (x + 2 * y + 7 * sequence) & 0xFFFFu
                                          : (x + y + sequence) & 0xFFu;
    }

    // --- V4l2Io ---
    int open(const char* path, int flags) override {
        if (unplugged || path != m_path) return fail(ENOENT);
        if ((flags & O_ACCMODE) != O_RDWR) return fail(EACCES);
        m_nonblocking = (flags & O_NONBLOCK) != 0;
        m_open = true;
        return kFd;
    }
    int close(int fd) override {
        if (fd != kFd || !m_open) return fail(EBADF);
        m_open = false;
        m_streaming = false;
        return 0;
    }
    int ioctl(int fd, unsigned long request, void* arg) override {
        if (fd != kFd || !m_open) return fail(EBADF);
        if (unplugged) return fail(ENODEV);
        switch (request) {
            case VIDIOC_QUERYCAP:
                return querycap(static_cast<v4l2_capability*>(arg));
            case VIDIOC_G_FMT:
                return g_fmt(static_cast<v4l2_format*>(arg));
            case VIDIOC_S_FMT:
                return s_fmt(static_cast<v4l2_format*>(arg));
            case VIDIOC_G_PARM:
                return g_parm(static_cast<v4l2_streamparm*>(arg));
            case VIDIOC_S_PARM:
                return s_parm(static_cast<v4l2_streamparm*>(arg));
            case VIDIOC_REQBUFS:
                return reqbufs(static_cast<v4l2_requestbuffers*>(arg));
            case VIDIOC_QUERYBUF:
                return querybuf(static_cast<v4l2_buffer*>(arg));
            case VIDIOC_QBUF:
                return qbuf(static_cast<v4l2_buffer*>(arg));
            case VIDIOC_DQBUF:
                return dqbuf(static_cast<v4l2_buffer*>(arg));
            case VIDIOC_STREAMON:
                return streamon(static_cast<int*>(arg));
            case VIDIOC_STREAMOFF:
                return streamoff(static_cast<int*>(arg));
            default:
                return fail(ENOTTY);
        }
    }
    void* mmap(std::size_t length, int prot, int flags, int fd, off_t offset) override {
        if (fd != kFd || (flags & MAP_SHARED) == 0 || (prot & PROT_READ) == 0) {
            errno = EINVAL;
            return MAP_FAILED;
        }
        for (auto& b : m_buffers) {
            if (static_cast<off_t>(b.offset) == offset && length <= b.data.size()) {
                b.mapped = true;
                return b.data.data();
            }
        }
        errno = EINVAL;
        return MAP_FAILED;
    }
    int munmap(void* address, std::size_t /*length*/) override {
        for (auto& b : m_buffers) {
            if (b.data.data() == address && b.mapped) {
                b.mapped = false;
                return 0;
            }
        }
        return fail(EINVAL);
    }
    int poll(pollfd* fds, nfds_t count, int timeout_ms) override {
        if (count != 1 || fds[0].fd != kFd) return fail(EINVAL);
        fds[0].revents = 0;
        if (unplugged || !m_streaming) {
            fds[0].revents = POLLERR;
            return 1;
        }
        if (spurious_wakeup_next) {
            spurious_wakeup_next = false;
            fds[0].revents = POLLIN;
            return 1;
        }
        if (m_done.empty() && timeout_ms > 0) produce_frame();
        if (m_done.empty()) return 0;
        fds[0].revents = POLLIN | POLLRDNORM;
        return 1;
    }

private:
    static constexpr int kFd = 42;
    struct Buffer {
        std::vector<std::uint8_t> data;
        std::uint32_t offset = 0;
        bool mapped = false;
        bool queued = false;
        v4l2_buffer meta{};
    };

    static int fail(int err) {
        errno = err;
        return -1;
    }
    std::uint32_t bytes_per_pixel() const { return m_format.fourcc == V4L2_PIX_FMT_Y16 ? 2u : 1u; }

    int querycap(v4l2_capability* cap) {
        *cap = {};
        std::strncpy(reinterpret_cast<char*>(cap->driver), "uvcvideo", sizeof cap->driver - 1);
        std::strncpy(reinterpret_cast<char*>(cap->card), "Boson: FLIR Video", sizeof cap->card - 1);
        std::strncpy(reinterpret_cast<char*>(cap->bus_info), "usb-0000:00:14.0-1",
                     sizeof cap->bus_info - 1);
        cap->device_caps = V4L2_CAP_VIDEO_CAPTURE | V4L2_CAP_STREAMING;
        cap->capabilities = cap->device_caps | V4L2_CAP_DEVICE_CAPS;
        return 0;
    }
    void fill_pix(v4l2_pix_format& pix) const {
        pix.pixelformat = m_format.fourcc;
        pix.width = m_format.width;
        pix.height = m_format.height;
        pix.field = V4L2_FIELD_NONE;
        pix.bytesperline = m_format.width * bytes_per_pixel();
        pix.sizeimage = pix.bytesperline * m_format.height;
    }
    int g_fmt(v4l2_format* f) {
        if (f->type != V4L2_BUF_TYPE_VIDEO_CAPTURE) return fail(EINVAL);
        fill_pix(f->fmt.pix);
        return 0;
    }
    int s_fmt(v4l2_format* f) {
        if (f->type != V4L2_BUF_TYPE_VIDEO_CAPTURE) return fail(EINVAL);
        if (!m_buffers.empty() || m_streaming) return fail(EBUSY);
        const Format* match = nullptr;
        for (const auto& candidate : formats)
            if (candidate.fourcc == f->fmt.pix.pixelformat) match = &candidate;
        if (match == nullptr) {
            if (refuse_unsupported_with_einval) return fail(EINVAL);
            match = &formats.front();
        }
        m_format = *match;  // discrete frame size: any requested size is adjusted to the format's
        fill_pix(f->fmt.pix);
        return 0;
    }
    int g_parm(v4l2_streamparm* p) {
        if (p->type != V4L2_BUF_TYPE_VIDEO_CAPTURE) return fail(EINVAL);
        p->parm.capture = {};
        p->parm.capture.capability = V4L2_CAP_TIMEPERFRAME;
        p->parm.capture.timeperframe = {1, m_rate_hz};
        return 0;
    }
    int s_parm(v4l2_streamparm* p) {
        if (p->type != V4L2_BUF_TYPE_VIDEO_CAPTURE) return fail(EINVAL);
        if (m_streaming) return fail(EBUSY);
        const auto& t = p->parm.capture.timeperframe;
        const double wanted =
            t.numerator == 0 ? 0.0 : static_cast<double>(t.denominator) / t.numerator;
        std::uint32_t best = frame_rates_hz.front();
        for (auto r : frame_rates_hz)
            if (std::abs(r - wanted) < std::abs(best - wanted)) best = r;
        m_rate_hz = best;  // the driver picks the nearest supported interval and reports it
        return g_parm(p);
    }
    int reqbufs(v4l2_requestbuffers* r) {
        if (r->type != V4L2_BUF_TYPE_VIDEO_CAPTURE || r->memory != V4L2_MEMORY_MMAP)
            return fail(EINVAL);
        if (m_streaming) return fail(EBUSY);
        if (mapped_count() != 0) return fail(EBUSY);
        m_buffers.clear();
        m_incoming.clear();
        m_done.clear();
        const std::uint32_t n = std::min(r->count, max_buffers);
        const std::size_t size = std::size_t{m_format.width} * m_format.height * bytes_per_pixel();
        for (std::uint32_t i = 0; i < n; ++i) {
            Buffer b;
            b.data.assign(size, 0);
            b.offset = i * 0x100000u;
            m_buffers.push_back(std::move(b));
        }
        r->count = n;
        return 0;
    }
    int querybuf(v4l2_buffer* b) {
        if (b->type != V4L2_BUF_TYPE_VIDEO_CAPTURE || b->index >= m_buffers.size())
            return fail(EINVAL);
        const Buffer& buf = m_buffers[b->index];
        b->length = static_cast<std::uint32_t>(buf.data.size());
        b->m.offset = buf.offset;
        b->flags =
            (buf.mapped ? V4L2_BUF_FLAG_MAPPED : 0u) | (buf.queued ? V4L2_BUF_FLAG_QUEUED : 0u);
        return 0;
    }
    int qbuf(v4l2_buffer* b) {
        if (b->type != V4L2_BUF_TYPE_VIDEO_CAPTURE || b->memory != V4L2_MEMORY_MMAP ||
            b->index >= m_buffers.size())
            return fail(EINVAL);
        Buffer& buf = m_buffers[b->index];
        if (buf.queued) return fail(EINVAL);
        buf.queued = true;
        m_incoming.push_back(b->index);
        return 0;
    }
    int dqbuf(v4l2_buffer* b) {
        if (b->type != V4L2_BUF_TYPE_VIDEO_CAPTURE || b->memory != V4L2_MEMORY_MMAP)
            return fail(EINVAL);
        if (!m_streaming) return fail(EINVAL);
        if (m_done.empty()) return fail(EAGAIN);  // the backend opens non-blocking
        const std::uint32_t index = m_done.front();
        m_done.pop_front();
        Buffer& buf = m_buffers[index];
        buf.queued = false;
        *b = buf.meta;
        return 0;
    }
    int streamon(int* type) {
        if (*type != V4L2_BUF_TYPE_VIDEO_CAPTURE || m_buffers.empty()) return fail(EINVAL);
        m_streaming = true;
        return 0;
    }
    int streamoff(int* type) {
        if (*type != V4L2_BUF_TYPE_VIDEO_CAPTURE) return fail(EINVAL);
        m_streaming = false;
        for (auto& b : m_buffers) b.queued = false;
        m_incoming.clear();
        m_done.clear();
        return 0;
    }

    void produce_frame() {
        if (frames_left == 0) return;
        if (frames_left > 0) --frames_left;
        next_sequence += skip_next;  // frames lost inside the device or on the bus
        skip_next = 0;
        const std::uint32_t sequence = next_sequence++;
        if (m_incoming.empty()) return;  // no buffer queued: this frame is lost
        const std::uint32_t index = m_incoming.front();
        m_incoming.pop_front();
        Buffer& buf = m_buffers[index];
        const std::uint32_t bpp = bytes_per_pixel();
        std::vector<std::uint16_t> words;
        if (fill_frame && bpp == 2) {
            words.assign(std::size_t{m_format.width} * m_format.height, 0);
            fill_frame(sequence, words);
        }
        for (std::uint32_t y = 0; y < m_format.height; ++y)
            for (std::uint32_t x = 0; x < m_format.width; ++x) {
                const std::uint32_t v = words.empty() ? pattern(m_format.fourcc, x, y, sequence)
                                                      : words[std::size_t{y} * m_format.width + x];
                const std::size_t at = (std::size_t{y} * m_format.width + x) * bpp;
                buf.data[at] = static_cast<std::uint8_t>(v & 0xFFu);
                if (bpp == 2) buf.data[at + 1] = static_cast<std::uint8_t>(v >> 8);
            }
        v4l2_buffer& meta = buf.meta;
        meta = {};
        meta.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        meta.memory = V4L2_MEMORY_MMAP;
        meta.index = index;
        meta.field = V4L2_FIELD_NONE;
        meta.sequence = sequence;
        meta.bytesused =
            static_cast<std::uint32_t>(short_next ? buf.data.size() / 2 : buf.data.size());
        meta.flags = V4L2_BUF_FLAG_MAPPED | V4L2_BUF_FLAG_DONE | V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC |
                     (corrupt_next ? V4L2_BUF_FLAG_ERROR : 0u);
        std::uint64_t t_us = std::uint64_t{sequence} * period_us();
        if (stamp_with_monotonic_clock) {
            timespec now{};
            clock_gettime(CLOCK_MONOTONIC, &now);
            t_us = static_cast<std::uint64_t>(now.tv_sec) * 1000000u +
                   static_cast<std::uint64_t>(now.tv_nsec) / 1000u;
        }
        meta.timestamp.tv_sec = static_cast<time_t>(t_us / 1000000u);
        meta.timestamp.tv_usec = static_cast<suseconds_t>(t_us % 1000000u);
        corrupt_next = false;
        short_next = false;
        m_done.push_back(index);
    }

    std::string m_path;
    bool m_open = false;
    bool m_nonblocking = false;
    bool m_streaming = false;
    Format m_format{V4L2_PIX_FMT_Y16, 160, 120};
    std::uint32_t m_rate_hz = 9;
    std::vector<Buffer> m_buffers;
    std::deque<std::uint32_t> m_incoming;  ///< queued by the application, waiting to be filled
    std::deque<std::uint32_t> m_done;      ///< filled, waiting for DQBUF
};

}  // namespace tirpol::test
