#include <fcntl.h>
#include <fmt/format.h>
#include <linux/usb/video.h>
#include <linux/uvcvideo.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "tirpol/acquisition/internal/lepton_control.h"

namespace tirpol::acquisition {

namespace {

/// UVCIOC_CTRL_QUERY on an open uvcvideo node: the kernel's own way to reach extension units.
class V4l2LeptonXu final : public LeptonXu {
public:
    V4l2LeptonXu(int fd, std::string path) : m_fd(fd), m_path(std::move(path)) {}
    ~V4l2LeptonXu() override { ::close(m_fd); }
    V4l2LeptonXu(const V4l2LeptonXu&) = delete;
    V4l2LeptonXu& operator=(const V4l2LeptonXu&) = delete;

    Status get(std::uint8_t unit, std::uint8_t selector, std::span<std::uint8_t> data) override {
        return query(unit, selector, UVC_GET_CUR, data.data(), data.size());
    }
    Status set(std::uint8_t unit, std::uint8_t selector,
               std::span<const std::uint8_t> data) override {
        std::vector<std::uint8_t> copy(data.begin(), data.end());  // the ioctl takes a non-const
        return query(unit, selector, UVC_SET_CUR, copy.data(), copy.size());
    }
    std::string name() const override { return m_path; }

private:
    Status query(std::uint8_t unit, std::uint8_t selector, std::uint8_t request, std::uint8_t* data,
                 std::size_t size) {
        uvc_xu_control_query q{};
        q.unit = unit;
        q.selector = selector;
        q.query = request;
        q.size = static_cast<__u16>(size);
        q.data = data;
        if (::ioctl(m_fd, UVCIOC_CTRL_QUERY, &q) == 0) return ok_status();
        const int e = errno;
        return DeviceError{
            e == ENOENT || e == EINVAL ? DeviceErrorCode::NotSupported : DeviceErrorCode::IoError,
            fmt::format("{}: UVCIOC_CTRL_QUERY unit {} selector {} ({} bytes): {}", m_path, unit,
                        selector, size, std::strerror(e))};
    }

    int m_fd;
    std::string m_path;
};

}  // namespace

Result<std::unique_ptr<LeptonXu>> open_v4l2_lepton_xu(const std::string& device_path) {
    const int fd = ::open(device_path.c_str(), O_RDWR | O_CLOEXEC);
    if (fd < 0)
        return DeviceError{DeviceErrorCode::IoError,
                           fmt::format("{}: cannot open the PureThermal video node: {}",
                                       device_path, std::strerror(errno))};
    return std::unique_ptr<LeptonXu>(std::make_unique<V4l2LeptonXu>(fd, device_path));
}

}  // namespace tirpol::acquisition
