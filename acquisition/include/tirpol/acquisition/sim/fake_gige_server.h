#pragma once
/// \file fake_gige_server.h
/// An in-process GigE Vision camera: Aravis's own fake camera server (ArvGvFakeCamera, the code
/// behind `arv-fake-gv-camera-0.8`) with the image content supplied by a C++ callback. It speaks
/// the real GVCP/GVSP protocols on a network interface (loopback by default), so
/// `aravis://<device_id()>` opens it like any camera. The digital twin hands out rendered frames
/// for the current polarizer angle.
///
/// Why the GigE Vision path: in Aravis 0.8.26 a fill-pattern callback cannot set the buffer's
/// received size (no public setter), so the in-process Fake interface delivers buffers whose image
/// size reads 0 (github.com/AravisProject/aravis/issues/955). The GigE Vision server sends the
/// whole payload regardless, and the receiving stream measures the size from the packets, so frames
/// arrive intact (tested in aravis_fake_server_test).

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace tirpol::acquisition {

/// What the camera is about to send.
struct FakeGigEFrameRequest {
    int width = 0, height = 0;
    /// "Mono8" … "Mono16", or a microgrid mosaic: "PolarizeMono8", "PolarizeMono12",
    /// "PolarizeMono12p", "PolarizeMono16" (the GenICam XML must offer it: the stock one does not)
    std::string pixel_format;
    int bits_per_pixel = 0;      ///< significant bits: values are clipped to [0, 2^bits − 1]
    std::uint64_t frame_id = 0;  ///< the GVSP block id of this frame (16-bit, never 0)
    std::uint32_t exposure_time_us = 0;
    std::uint32_t gain = 0;
    /// Host CLOCK_REALTIME (ns) at which Aravis stamped this frame, just before filling it: the end
    /// of its exposure. The camera free-runs, so a time-true fill renders the scene as it was over
    /// the exposure that ended here (e.g. the polarizer angle of a turning stage).
    std::int64_t timestamp_ns = 0;
};

/// Writes width × height counts, row-major (the vector arrives sized). Runs on the server's thread.
using FakeGigEFill =
    std::function<void(const FakeGigEFrameRequest& request, std::vector<float>& counts)>;

struct FakeGigECameraOptions {
    std::string interface = "127.0.0.1";  ///< interface name or IPv4 address to serve on
    std::string serial = "GV01";          ///< device id becomes "Aravis-Fake-<serial>"
    std::filesystem::path genicam_xml;    ///< empty: Aravis's built-in arv-fake-camera.xml
    /// Fraction of GVSP packets the server does not send (Aravis's "gvsp-lost-ratio"): frames that
    /// arrive incomplete or not at all, as on a congested link. 0: none.
    double lost_packet_ratio = 0.0;
};

class FakeGigECameraServer {
public:
    /// Starts serving; throws tirpol::Error naming the interface when it cannot (address in use, no
    /// such interface, unreadable XML).
    explicit FakeGigECameraServer(FakeGigECameraOptions options = {});
    ~FakeGigECameraServer();
    FakeGigECameraServer(const FakeGigECameraServer&) = delete;
    FakeGigECameraServer& operator=(const FakeGigECameraServer&) = delete;

    /// Replaces the image source; an empty function restores Aravis's diagonal-ramp test pattern.
    /// With a callback set, frames in pixel formats other than those above are sent unfilled.
    void set_fill(FakeGigEFill fill);
    /// Aravis's device id of this camera ("Aravis-Fake-<serial>"), for aravis://.
    std::string device_id() const;
    const std::string& interface() const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace tirpol::acquisition
