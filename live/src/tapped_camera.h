#pragma once
/// \file tapped_camera.h
/// A Camera whose frames come from the live view's grab thread (a FrameTap) instead of the device,
/// so that the acquisition code written for a Camera — the capture loop of `tirpol acquire` — runs
/// unchanged while the page keeps showing every frame. start() opens the tap (frames from then on),
/// stop() closes it; the device itself keeps streaming under the FrameFeed.

#include <memory>

#include "frame_feed.h"

namespace tirpol::live {

class TappedCamera final : public acquisition::Camera {
public:
    /// `feed` must outlive this camera and be running.
    explicit TappedCamera(FrameFeed& feed) : m_feed(feed) {}

    acquisition::CameraInfo info() const override { return m_feed.camera_info(); }
    /// The device's format is fixed while the live view runs: a different one is NotSupported.
    acquisition::Status set_pixel_format(const std::string& format) override;
    acquisition::Status set_frame_rate(double hz) override;
    acquisition::Status start() override;
    acquisition::Status stop() override;
    acquisition::Result<acquisition::Frame> grab(std::chrono::milliseconds timeout) override;
    /// The device's counts (drops are the device's, whoever reads the frames), as the grab thread
    /// read them.
    acquisition::StreamStatistics statistics() const override { return m_feed.camera_statistics(); }
    /// The feed's last FPA sample: only the grab thread talks to the device.
    std::optional<double> device_temperature_k() override { return m_feed.fpa_temperature_k(); }

private:
    FrameFeed& m_feed;
    std::shared_ptr<FrameTap> m_tap;
};

}  // namespace tirpol::live
