#include "tapped_camera.h"

namespace tirpol::live {

using namespace acquisition;

Status TappedCamera::set_pixel_format(const std::string& format) {
    if (format == m_feed.camera_info().pixel_format) return ok_status();
    return DeviceError{DeviceErrorCode::NotSupported,
                       "live view: the camera streams " + m_feed.camera_info().pixel_format +
                           "; it cannot switch to " + format + " while the page is live"};
}

Status TappedCamera::set_frame_rate(double hz) {
    const auto rate = m_feed.camera_info().frame_rate_hz;
    if (rate && *rate == hz) return ok_status();
    return DeviceError{
        DeviceErrorCode::NotSupported,
        "live view: the camera's frame rate is fixed while the page is live (asked " +
            std::to_string(hz) + " Hz)"};
}

Status TappedCamera::start() {
    if (!m_tap) m_tap = m_feed.open_tap();
    return ok_status();
}

Status TappedCamera::stop() {
    m_tap.reset();
    return ok_status();
}

Result<Frame> TappedCamera::grab(std::chrono::milliseconds timeout) {
    if (!m_tap)
        return DeviceError{DeviceErrorCode::InvalidArgument, "live view: grab() before start()"};
    return m_tap->next(timeout);
}

}  // namespace tirpol::live
