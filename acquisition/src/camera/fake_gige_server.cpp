#include "tirpol/acquisition/sim/fake_gige_server.h"

#include <arv.h>

#include <algorithm>
#include <cmath>
#include <mutex>

#include "camera/aravis_support.h"
#include "camera/pixel_formats.h"
#include "tirpol/core/error.h"

namespace tirpol::acquisition {

struct FakeGigECameraServer::Impl {
    FakeGigECameraOptions options;
    aravis::GObjectPtr<ArvGvFakeCamera> server;
    std::mutex mutex;  ///< guards fill against set_fill while the server thread renders
    FakeGigEFill fill;
    std::vector<float> counts;

    /// ArvFakeCameraFillPattern: called by the server thread (under Aravis's fill-pattern mutex)
    /// for each frame, after Aravis has set the buffer's frame id, width, height and pixel format.
    static void fill_pattern(ArvBuffer* buffer, void* data, guint32 exposure_time_us, guint32 gain,
                             ArvPixelFormat pixel_format) {
        auto* self = static_cast<Impl*>(data);
        std::lock_guard lock(self->mutex);
        const GenICamPixelFormat* format =
            find_pixel_format(static_cast<std::uint32_t>(pixel_format));
        FakeGigEFrameRequest request;
        request.width = arv_buffer_get_image_width(buffer);
        request.height = arv_buffer_get_image_height(buffer);
        if (!self->fill || format == nullptr || request.width <= 0 || request.height <= 0) return;
        request.pixel_format = format->name;
        request.bits_per_pixel = format->significant_bits;
        request.frame_id = arv_buffer_get_frame_id(buffer);
        request.exposure_time_us = exposure_time_us;
        request.gain = gain;
        request.timestamp_ns = static_cast<std::int64_t>(arv_buffer_get_timestamp(buffer));
        const std::size_t n =
            static_cast<std::size_t>(request.width) * static_cast<std::size_t>(request.height);
        self->counts.assign(n, 0.0f);
        self->fill(request, self->counts);
        if (self->counts.size() != n) return;
        // The buffer was allocated with the camera's payload (width × height × bytes per pixel);
        // the public API only hands out a const pointer (and a size that is still 0 here), so write
        // through it.
        auto* out =
            static_cast<std::uint8_t*>(const_cast<void*>(arv_buffer_get_data(buffer, nullptr)));
        const double full_scale = std::ldexp(1.0, format->significant_bits) - 1.0;
        const auto width = static_cast<std::size_t>(request.width);
        const std::size_t row = row_bytes(*format, request.width);
        for (std::size_t i = 0; i < n; ++i) {
            const double v = std::isfinite(self->counts[i])
                                 ? std::clamp(std::nearbyint(static_cast<double>(self->counts[i])),
                                              0.0, full_scale)
                                 : 0.0;
            const auto value = static_cast<std::uint16_t>(v);
            if (format->stored_bits == 8) {
                out[i] = static_cast<std::uint8_t>(value);
            } else if (format->stored_bits == 12) {  // PFNC Mono12p: see pixel_decode.h
                const std::size_t x = i % width;
                std::uint8_t* pair = out + (i / width) * row + 3 * (x / 2);
                if (x % 2 == 0) {
                    pair[0] = static_cast<std::uint8_t>(value & 0xFFu);
                    pair[1] = static_cast<std::uint8_t>((pair[1] & 0xF0u) | (value >> 8u));
                } else {
                    pair[1] =
                        static_cast<std::uint8_t>((pair[1] & 0x0Fu) | ((value & 0x0Fu) << 4u));
                    pair[2] = static_cast<std::uint8_t>(value >> 4u);
                }
            } else {  // PFNC MonoN unpacked: little-endian 16-bit words
                out[2 * i] = static_cast<std::uint8_t>(value & 0xFFu);
                out[2 * i + 1] = static_cast<std::uint8_t>(value >> 8u);
            }
        }
    }
};

FakeGigECameraServer::FakeGigECameraServer(FakeGigECameraOptions options)
    : m_impl(std::make_unique<Impl>()) {
    m_impl->options = std::move(options);
    const auto& o = m_impl->options;
    if (!o.genicam_xml.empty() && !std::filesystem::is_regular_file(o.genicam_xml))
        fail("fake GigE camera: GenICam file '{}' not found", o.genicam_xml.string());
    m_impl->server.reset(
        arv_gv_fake_camera_new_full(o.interface.c_str(), o.serial.c_str(),
                                    o.genicam_xml.empty() ? nullptr : o.genicam_xml.c_str()));
    if (!m_impl->server || !arv_gv_fake_camera_is_running(m_impl->server.get()))
        fail(
            "fake GigE camera: cannot serve on interface '{}' (no such interface, or port 3956 in "
            "use)",
            o.interface);
    if (!(o.lost_packet_ratio >= 0.0 && o.lost_packet_ratio < 1.0))
        fail("fake GigE camera: lost packet ratio {} (expected in [0, 1))", o.lost_packet_ratio);
    if (o.lost_packet_ratio > 0.0)
        g_object_set(m_impl->server.get(), "gvsp-lost-ratio", o.lost_packet_ratio, nullptr);
}

FakeGigECameraServer::~FakeGigECameraServer() {
    // Finalizing the server joins its thread before the callback state goes away.
    m_impl->server.reset();
}

void FakeGigECameraServer::set_fill(FakeGigEFill fill) {
    const bool custom = static_cast<bool>(fill);
    {
        std::lock_guard lock(m_impl->mutex);
        m_impl->fill = std::move(fill);
    }
    // Outside our mutex: the server thread holds Aravis's fill-pattern mutex while it calls
    // fill_pattern, which takes ours, so taking them in the other order here could deadlock.
    ArvFakeCamera* camera = arv_gv_fake_camera_get_fake_camera(m_impl->server.get());
    if (custom)
        arv_fake_camera_set_fill_pattern(camera, &Impl::fill_pattern, m_impl.get());
    else
        arv_fake_camera_set_fill_pattern(camera, nullptr, nullptr);  // Aravis's diagonal ramp
}

std::string FakeGigECameraServer::device_id() const {
    return "Aravis-Fake-" + m_impl->options.serial;
}

const std::string& FakeGigECameraServer::interface() const { return m_impl->options.interface; }

}  // namespace tirpol::acquisition
