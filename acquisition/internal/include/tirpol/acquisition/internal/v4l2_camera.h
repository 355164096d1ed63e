#pragma once
/// \file v4l2_camera.h
/// UVC thermal cores (FLIR Boson, Lepton on PureThermal boards) through Video4Linux2:
/// `v4l2:///dev/videoN[?format=Y16|GREY&width=W&height=H&fps=F&buffers=N]`.
/// Streaming I/O with memory-mapped buffers (kernel docs, "Streaming I/O (Memory Mapping)"):
/// VIDIOC_REQBUFS → VIDIOC_QUERYBUF + mmap per buffer → VIDIOC_QBUF all → VIDIOC_STREAMON, then
/// poll() + VIDIOC_DQBUF / VIDIOC_QBUF per frame; `v4l2_buffer.sequence` gaps are dropped frames.
/// Every system call goes through V4l2Io so the backend can be tested without a kernel device.

#include <poll.h>
#include <sys/types.h>

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/acquisition/camera.h"

namespace tirpol::acquisition {

/// The system calls the V4L2 backend makes, with their POSIX contracts (return −1 and set errno on
/// failure). The real implementation forwards to the kernel; tests substitute a fake device.
class V4l2Io {
public:
    virtual ~V4l2Io() = default;
    virtual int open(const char* path, int flags) = 0;
    virtual int close(int fd) = 0;
    virtual int ioctl(int fd, unsigned long request, void* arg) = 0;
    virtual void* mmap(std::size_t length, int prot, int flags, int fd,
                       off_t offset) = 0;  ///< MAP_FAILED on error
    virtual int munmap(void* address, std::size_t length) = 0;
    virtual int poll(pollfd* fds, nfds_t count, int timeout_ms) = 0;
};

/// The kernel: ::open, ::close, ::ioctl (retried on EINTR), ::mmap, ::munmap, ::poll.
std::shared_ptr<V4l2Io> system_v4l2_io();

struct V4l2CameraOptions {
    std::optional<std::string> pixel_format;  ///< "Y16" (16-bit little-endian) or "GREY" (8-bit)
    std::optional<int> width, height;
    std::optional<double>
        frame_rate_hz;     ///< via VIDIOC_S_PARM when the driver has V4L2_CAP_TIMEPERFRAME
    unsigned buffers = 4;  ///< requested; the driver may grant fewer (at least 2 are needed)
    /// A microgrid (division-of-focal-plane) sensor's analyzer angles at cell positions (0,0),
    /// (0,1), (1,0), (1,1), degrees (URI key `microgrid=`, "sony" or four angles): V4L2 has no
    /// polarized pixel format, so a microgrid camera streaming Y16/GREY declares its pattern, and
    /// CameraInfo::microgrid_pattern_deg (and so the session) carries it. Absent: no microgrid.
    std::optional<std::array<double, 4>> microgrid_pattern_deg;
};

/// A /dev/video* node that is a streaming video-capture device (UVC also creates metadata nodes:
/// skipped).
struct V4l2DeviceInfo {
    std::string path;  ///< e.g. /dev/video0
    std::string driver, card, bus_info;
};

/// Lists the capture devices among /dev/video* (VIDIOC_QUERYCAP on each).
std::vector<V4l2DeviceInfo> discover_v4l2_cameras(
    const std::shared_ptr<V4l2Io>& io = system_v4l2_io());

/// Opens `device_path` (e.g. /dev/video0) non-blocking, checks it can capture and stream, applies
/// `options`.
Result<std::unique_ptr<Camera>> open_v4l2_camera(const std::string& device_path,
                                                 const V4l2CameraOptions& options = {},
                                                 std::shared_ptr<V4l2Io> io = system_v4l2_io());

}  // namespace tirpol::acquisition
