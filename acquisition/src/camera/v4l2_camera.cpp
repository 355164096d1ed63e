// v4l2:///dev/videoN — memory-mapped streaming I/O, following the kernel's V4L2 API documentation
// ("Streaming I/O (Memory Mapping)", "ioctl VIDIOC_REQBUFS", "ioctl VIDIOC_QBUF, VIDIOC_DQBUF",
// "struct v4l2_buffer"), through the V4l2Io seam.

#include "tirpol/acquisition/internal/v4l2_camera.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <linux/videodev2.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <vector>

#include "camera/pixel_decode.h"
#include "tirpol/acquisition/internal/frame_id.h"

namespace tirpol::acquisition {

namespace {

class SystemV4l2Io final : public V4l2Io {
public:
    int open(const char* path, int flags) override { return ::open(path, flags); }
    int close(int fd) override { return ::close(fd); }
    int ioctl(int fd, unsigned long request, void* arg) override {
        int r = 0;
        do {
            r = ::ioctl(fd, request, arg);
        } while (r == -1 && errno == EINTR);
        return r;
    }
    void* mmap(std::size_t length, int prot, int flags, int fd, off_t offset) override {
        return ::mmap(nullptr, length, prot, flags, fd, offset);
    }
    int munmap(void* address, std::size_t length) override { return ::munmap(address, length); }
    int poll(pollfd* fds, nfds_t count, int timeout_ms) override {
        return ::poll(fds, count, timeout_ms);
    }
};

DeviceErrorCode classify_errno(int err) {
    switch (err) {
        case ENODEV:
        case ENXIO:
        case ENOENT:
            return DeviceErrorCode::Disconnected;
        case EINVAL:
        case ERANGE:
            return DeviceErrorCode::InvalidArgument;
        case ENOTTY:
            return DeviceErrorCode::NotSupported;
        case ETIMEDOUT:
        case EAGAIN:
            return DeviceErrorCode::Timeout;
        default:
            return DeviceErrorCode::IoError;
    }
}

std::string fourcc_text(std::uint32_t f) {
    std::string s;
    for (int i = 0; i < 4; ++i) s += static_cast<char>((f >> (8 * i)) & 0xFFu);
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s;
}

std::optional<std::uint32_t> fourcc_of(const std::string& name) {
    if (name == "Y16") return V4L2_PIX_FMT_Y16;
    if (name == "GREY") return V4L2_PIX_FMT_GREY;
    return std::nullopt;
}

std::int64_t realtime_now_ns() {
    timespec ts{};
    clock_gettime(CLOCK_REALTIME, &ts);
    return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

struct MappedBuffer {
    void* address = nullptr;
    std::size_t length = 0;
};

class V4l2Camera final : public Camera {
public:
    V4l2Camera(std::string path, std::shared_ptr<V4l2Io> io, int fd, V4l2CameraOptions options)
        : m_path(std::move(path)),
          m_label("v4l2://" + m_path),
          m_io(std::move(io)),
          m_fd(fd),
          m_options(std::move(options)) {}

    ~V4l2Camera() override {
        if (m_streaming) stop();
        release_buffers();
        m_io->close(m_fd);
    }

    Status configure() {
        v4l2_capability cap{};
        if (xioctl(VIDIOC_QUERYCAP, &cap) != 0) return errno_error("VIDIOC_QUERYCAP");
        const std::uint32_t caps =
            (cap.capabilities & V4L2_CAP_DEVICE_CAPS) != 0 ? cap.device_caps : cap.capabilities;
        if ((caps & V4L2_CAP_VIDEO_CAPTURE) == 0)
            return DeviceError{DeviceErrorCode::NotSupported,
                               m_label + ": not a video capture device"};
        if ((caps & V4L2_CAP_STREAMING) == 0)
            return DeviceError{DeviceErrorCode::NotSupported,
                               m_label + ": no streaming I/O (V4L2_CAP_STREAMING)"};
        m_info.uri = m_label;
        m_info.microgrid_pattern_deg = m_options.microgrid_pattern_deg;
        m_info.vendor = reinterpret_cast<const char*>(cap.driver);
        m_info.model = reinterpret_cast<const char*>(cap.card);
        m_info.serial = reinterpret_cast<const char*>(cap.bus_info);
        if (m_options.pixel_format || m_options.width || m_options.height) {
            if (Status s = apply_format(); !s) return s;
        }
        if (m_options.frame_rate_hz) {
            if (Status s = set_frame_rate(*m_options.frame_rate_hz); !s) return s;
        }
        return read_format();
    }

    CameraInfo info() const override { return m_info; }

    Status set_pixel_format(const std::string& format) override {
        if (m_streaming) return busy("set_pixel_format");
        m_options.pixel_format = format;
        if (Status s = apply_format(); !s) return s;
        return read_format();
    }

    Status set_frame_rate(double hz) override {
        if (m_streaming) return busy("set_frame_rate");
        if (!(hz > 0.0) || !std::isfinite(hz))
            return DeviceError{DeviceErrorCode::InvalidArgument,
                               fmt::format("{}: frame rate {} Hz", m_label, hz)};
        v4l2_streamparm parm{};
        parm.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        if (xioctl(VIDIOC_G_PARM, &parm) != 0) return errno_error("VIDIOC_G_PARM");
        if ((parm.parm.capture.capability & V4L2_CAP_TIMEPERFRAME) == 0)
            return DeviceError{DeviceErrorCode::NotSupported,
                               m_label + ": the driver has no frame-interval control"};
        // timeperframe is the frame interval as a fraction of seconds; 1/hz with a microsecond
        // denominator.
        parm.parm.capture.timeperframe.numerator = 1000;
        parm.parm.capture.timeperframe.denominator =
            static_cast<std::uint32_t>(std::lround(hz * 1000.0));
        if (xioctl(VIDIOC_S_PARM, &parm) != 0) return errno_error("VIDIOC_S_PARM");
        const auto& tpf = parm.parm.capture.timeperframe;
        if (tpf.numerator != 0)
            m_info.frame_rate_hz = static_cast<double>(tpf.denominator) / tpf.numerator;
        return ok_status();
    }

    Status start() override {
        if (m_streaming) return ok_status();
        v4l2_requestbuffers req{};
        req.count = m_options.buffers;
        req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        req.memory = V4L2_MEMORY_MMAP;
        if (xioctl(VIDIOC_REQBUFS, &req) != 0) return errno_error("VIDIOC_REQBUFS");
        m_allocated = true;
        if (req.count < 2) {
            release_buffers();
            return DeviceError{
                DeviceErrorCode::DeviceFault,
                fmt::format("{}: the driver granted {} buffer(s); streaming needs at least 2",
                            m_label, req.count)};
        }
        for (std::uint32_t i = 0; i < req.count; ++i) {
            v4l2_buffer buf = make_buffer(i);
            if (xioctl(VIDIOC_QUERYBUF, &buf) != 0) return fail_start("VIDIOC_QUERYBUF");
            void* address =
                m_io->mmap(buf.length, PROT_READ | PROT_WRITE, MAP_SHARED, m_fd, buf.m.offset);
            if (address == MAP_FAILED) return fail_start("mmap");
            m_buffers.push_back({address, buf.length});
        }
        for (std::uint32_t i = 0; i < req.count; ++i) {
            v4l2_buffer buf = make_buffer(i);
            if (xioctl(VIDIOC_QBUF, &buf) != 0) return fail_start("VIDIOC_QBUF");
        }
        int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        if (xioctl(VIDIOC_STREAMON, &type) != 0) return fail_start("VIDIOC_STREAMON");
        m_ids.restart();
        m_streaming = true;
        return ok_status();
    }

    Status stop() override {
        if (!m_streaming) return ok_status();
        m_streaming = false;
        int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        // STREAMOFF dequeues every buffer (kernel docs, VIDIOC_STREAMON/STREAMOFF), so the buffers
        // can be freed.
        const int r = xioctl(VIDIOC_STREAMOFF, &type);
        const int err = errno;
        release_buffers();
        if (r != 0) {
            errno = err;
            return errno_error("VIDIOC_STREAMOFF");
        }
        return ok_status();
    }

    Result<Frame> grab(std::chrono::milliseconds timeout) override {
        if (!m_streaming)
            return DeviceError{DeviceErrorCode::InvalidArgument,
                               m_label + ": grab() before start()"};
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        for (;;) {
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                deadline - std::chrono::steady_clock::now());
            pollfd pfd{m_fd, POLLIN, 0};
            const int ready =
                m_io->poll(&pfd, 1, static_cast<int>(std::max<std::int64_t>(0, left.count())));
            if (ready < 0) {
                if (errno == EINTR) continue;
                return errno_error("poll");
            }
            if (ready == 0)
                return DeviceError{
                    DeviceErrorCode::Timeout,
                    fmt::format("{}: no frame within {} ms", m_label, timeout.count())};
            if ((pfd.revents & (POLLERR | POLLHUP | POLLNVAL)) != 0)
                return DeviceError{DeviceErrorCode::Disconnected,
                                   m_label + ": the device reported an error (POLLERR)"};
            v4l2_buffer buf = make_buffer(0);
            if (xioctl(VIDIOC_DQBUF, &buf) != 0) {
                if (errno == EAGAIN) continue;  // readiness without a buffer: poll again
                return errno_error("VIDIOC_DQBUF");
            }
            Frame frame;
            const bool complete = take(buf, frame);
            if (xioctl(VIDIOC_QBUF, &buf) != 0) return errno_error("VIDIOC_QBUF");
            if (complete) return frame;
            if (std::chrono::steady_clock::now() >= deadline)
                return DeviceError{
                    DeviceErrorCode::Timeout,
                    fmt::format("{}: no complete frame within {} ms", m_label, timeout.count())};
        }
    }

    StreamStatistics statistics() const override { return m_stats; }

private:
    int xioctl(unsigned long request, void* arg) { return m_io->ioctl(m_fd, request, arg); }

    DeviceError errno_error(const char* call) const {
        const int err = errno;
        return {classify_errno(err), fmt::format("{}: {} failed: {} (errno {})", m_label, call,
                                                 std::strerror(err), err)};
    }

    DeviceError busy(const char* what) const {
        return {DeviceErrorCode::InvalidArgument,
                fmt::format("{}: {} while streaming; stop() first", m_label, what)};
    }

    Status fail_start(const char* call) {
        const DeviceError error = errno_error(call);
        release_buffers();
        return error;
    }

    static v4l2_buffer make_buffer(std::uint32_t index) {
        v4l2_buffer buf{};
        buf.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        buf.memory = V4L2_MEMORY_MMAP;
        buf.index = index;
        return buf;
    }

    void release_buffers() {
        for (const auto& b : m_buffers) m_io->munmap(b.address, b.length);
        m_buffers.clear();
        if (m_allocated) {
            v4l2_requestbuffers req{};
            req.count = 0;  // frees the driver's buffers
            req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
            req.memory = V4L2_MEMORY_MMAP;
            xioctl(VIDIOC_REQBUFS, &req);
            m_allocated = false;
        }
    }

    Status apply_format() {
        v4l2_format fmt{};
        fmt.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        if (xioctl(VIDIOC_G_FMT, &fmt) != 0) return errno_error("VIDIOC_G_FMT");
        if (m_options.pixel_format) {
            const auto fourcc = fourcc_of(*m_options.pixel_format);
            if (!fourcc)
                return DeviceError{DeviceErrorCode::InvalidArgument,
                                   fmt::format("{}: pixel format '{}' (expected Y16 or GREY)",
                                               m_label, *m_options.pixel_format)};
            fmt.fmt.pix.pixelformat = *fourcc;
        }
        if (m_options.width) fmt.fmt.pix.width = static_cast<std::uint32_t>(*m_options.width);
        if (m_options.height) fmt.fmt.pix.height = static_cast<std::uint32_t>(*m_options.height);
        fmt.fmt.pix.field = V4L2_FIELD_NONE;
        fmt.fmt.pix.bytesperline = 0;  // let the driver choose the stride
        const std::uint32_t wanted = fmt.fmt.pix.pixelformat;
        const std::uint32_t wanted_w = fmt.fmt.pix.width, wanted_h = fmt.fmt.pix.height;
        if (xioctl(VIDIOC_S_FMT, &fmt) != 0) {
            // Older drivers refuse an unsupported format with EINVAL.
            if (errno == EINVAL)
                return DeviceError{DeviceErrorCode::NotSupported,
                                   fmt::format("{}: the driver refused format {} {}×{} (EINVAL)",
                                               m_label, fourcc_text(wanted), wanted_w, wanted_h)};
            return errno_error("VIDIOC_S_FMT");
        }
        // Current drivers adjust instead of failing: a different format or size means "not
        // available".
        if (fmt.fmt.pix.pixelformat != wanted || fmt.fmt.pix.width != wanted_w ||
            fmt.fmt.pix.height != wanted_h)
            return DeviceError{DeviceErrorCode::NotSupported,
                               fmt::format("{}: asked for {} {}×{}, the driver offers {} {}×{}",
                                           m_label, fourcc_text(wanted), wanted_w, wanted_h,
                                           fourcc_text(fmt.fmt.pix.pixelformat), fmt.fmt.pix.width,
                                           fmt.fmt.pix.height)};
        return ok_status();
    }

    Status read_format() {
        v4l2_format fmt{};
        fmt.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        if (xioctl(VIDIOC_G_FMT, &fmt) != 0) return errno_error("VIDIOC_G_FMT");
        m_fourcc = fmt.fmt.pix.pixelformat;
        if (m_fourcc != V4L2_PIX_FMT_Y16 && m_fourcc != V4L2_PIX_FMT_GREY)
            return DeviceError{
                DeviceErrorCode::NotSupported,
                fmt::format("{}: current format {} is neither Y16 nor GREY; open with ?format=Y16",
                            m_label, fourcc_text(m_fourcc))};
        m_info.pixel_format = fourcc_text(m_fourcc);
        m_info.bits_per_pixel = m_fourcc == V4L2_PIX_FMT_Y16 ? 16 : 8;
        m_info.width = static_cast<int>(fmt.fmt.pix.width);
        m_info.height = static_cast<int>(fmt.fmt.pix.height);
        const std::size_t min_stride = static_cast<std::size_t>(m_info.width) *
                                       static_cast<std::size_t>(m_info.bits_per_pixel / 8);
        m_stride = std::max<std::size_t>(fmt.fmt.pix.bytesperline, min_stride);
        return ok_status();
    }

    /// When the frame reached the host, on CLOCK_REALTIME. A buffer may wait in the queue long
    /// after the driver filled it (a free-running camera keeps filling while nobody dequeues), so
    /// the time of DQBUF says nothing about the frame: map the driver's CLOCK_MONOTONIC stamp to
    /// CLOCK_REALTIME with the offset between the two clocks now. A start-of-exposure stamp
    /// (V4L2_BUF_FLAG_TSTAMP_SRC_SOE) is used as is: earlier than reception, so the capture loop's
    /// gate only gets stricter. Without a monotonic stamp (or one from the future) the dequeue time
    /// is the only bound there is.
    static std::int64_t reception_realtime_ns(const v4l2_buffer& buf, std::int64_t stamp_ns) {
        const std::int64_t now_real = realtime_now_ns();
        if ((buf.flags & V4L2_BUF_FLAG_TIMESTAMP_MASK) != V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC ||
            stamp_ns <= 0)
            return now_real;
        timespec mono{};
        clock_gettime(CLOCK_MONOTONIC, &mono);
        const std::int64_t now_mono =
            static_cast<std::int64_t>(mono.tv_sec) * 1'000'000'000 + mono.tv_nsec;
        if (stamp_ns > now_mono) return now_real;
        return now_real - (now_mono - stamp_ns);
    }

    bool take(const v4l2_buffer& buf, Frame& frame) {
        const FrameIdStep step = m_ids.next(buf.sequence);
        m_stats.dropped += step.missed;
        const auto bytes_per_pixel = static_cast<std::size_t>(m_info.bits_per_pixel / 8);
        const std::size_t needed = m_stride * static_cast<std::size_t>(m_info.height - 1) +
                                   static_cast<std::size_t>(m_info.width) * bytes_per_pixel;
        // V4L2_BUF_FLAG_ERROR: "the buffer was dequeued successfully, although the data might have
        // been corrupted".
        if ((buf.flags & V4L2_BUF_FLAG_ERROR) != 0 || buf.index >= m_buffers.size() ||
            buf.bytesused < needed || step.duplicate) {
            ++m_stats.incomplete;
            return false;
        }
        frame.width = m_info.width;
        frame.height = m_info.height;
        frame.frame_id = step.id;
        decode_mono(static_cast<const std::uint8_t*>(m_buffers[buf.index].address), frame.width,
                    frame.height, static_cast<int>(bytes_per_pixel), m_stride, frame.counts);
        // uvcvideo stamps buffers with CLOCK_MONOTONIC (V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC).
        frame.device_timestamp_ns =
            static_cast<std::int64_t>(buf.timestamp.tv_sec) * 1'000'000'000 +
            static_cast<std::int64_t>(buf.timestamp.tv_usec) * 1000;
        frame.host_timestamp_ns = reception_realtime_ns(buf, frame.device_timestamp_ns);
        ++m_stats.delivered;
        return true;
    }

    std::string m_path, m_label;
    std::shared_ptr<V4l2Io> m_io;
    int m_fd;
    V4l2CameraOptions m_options;
    CameraInfo m_info;
    std::uint32_t m_fourcc = 0;
    std::size_t m_stride = 0;
    std::vector<MappedBuffer> m_buffers;
    bool m_allocated = false;
    bool m_streaming = false;
    FrameIdUnwrapper m_ids = FrameIdUnwrapper::v4l2_sequence();
    StreamStatistics m_stats;
};

}  // namespace

std::shared_ptr<V4l2Io> system_v4l2_io() { return std::make_shared<SystemV4l2Io>(); }

std::vector<V4l2DeviceInfo> discover_v4l2_cameras(const std::shared_ptr<V4l2Io>& io) {
    std::vector<V4l2DeviceInfo> found;
    std::error_code ec;
    std::vector<std::string> paths;
    for (const auto& entry : std::filesystem::directory_iterator("/dev", ec)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("video", 0) == 0) paths.push_back(entry.path().string());
    }
    std::sort(paths.begin(), paths.end());
    for (const auto& path : paths) {
        const int fd = io->open(path.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
        if (fd < 0) continue;
        v4l2_capability cap{};
        if (io->ioctl(fd, VIDIOC_QUERYCAP, &cap) == 0) {
            const std::uint32_t caps =
                (cap.capabilities & V4L2_CAP_DEVICE_CAPS) != 0 ? cap.device_caps : cap.capabilities;
            if ((caps & V4L2_CAP_VIDEO_CAPTURE) != 0 && (caps & V4L2_CAP_STREAMING) != 0)
                found.push_back({path, reinterpret_cast<const char*>(cap.driver),
                                 reinterpret_cast<const char*>(cap.card),
                                 reinterpret_cast<const char*>(cap.bus_info)});
        }
        io->close(fd);
    }
    return found;
}

Result<std::unique_ptr<Camera>> open_v4l2_camera(const std::string& device_path,
                                                 const V4l2CameraOptions& options,
                                                 std::shared_ptr<V4l2Io> io) {
    // Non-blocking: DQBUF returns EAGAIN instead of sleeping; grab() waits in poll() with its
    // timeout.
    const int fd = io->open(device_path.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        const int err = errno;
        return DeviceError{classify_errno(err), fmt::format("v4l2://{}: open failed: {} (errno {})",
                                                            device_path, std::strerror(err), err)};
    }
    auto camera = std::make_unique<V4l2Camera>(device_path, std::move(io), fd, options);
    if (Status s = camera->configure(); !s) return s.error();
    return std::unique_ptr<Camera>(std::move(camera));
}

}  // namespace tirpol::acquisition
