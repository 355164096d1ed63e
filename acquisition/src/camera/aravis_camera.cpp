// aravis://<device-id>: a GenICam camera through Aravis 0.8's C API (ArvCamera, ArvStream, ArvGc).

#include "tirpol/acquisition/internal/aravis_camera.h"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <ctime>
#include <thread>

#include "camera/aravis_support.h"
#include "camera/gvcp_probe.h"
#include "camera/pixel_decode.h"
#include "camera/pixel_formats.h"
#include "tirpol/acquisition/internal/frame_id.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::acquisition {

using aravis::GErrorSlot;
using aravis::GObjectPtr;
using aravis::to_device_error;

namespace {

constexpr std::array kTemperatureFeatures = {"DeviceTemperature", "SensorTemperature",
                                             "FPATemperature", "FpaTemperature", "CoreTemperature"};
/// FLIR-style radiometric (Planck) calibration constants: L = R / (exp(B / T) − F) + O, with R = R1
/// / R2 on cameras that split it (FLIR's radiometric file metadata calls them PlanckR1, PlanckR2,
/// PlanckB, PlanckF, PlanckO).
constexpr std::array kPlanckFeatures = {"R", "R1", "R2", "B", "F", "O"};

std::string supported_pixel_formats() {
    std::string names;
    for (const auto& f : kGenICamPixelFormats)
        names += (names.empty() ? "" : ", ") + std::string(f.name);
    return names;
}

std::int64_t realtime_now_ns() {
    timespec ts{};
    clock_gettime(CLOCK_REALTIME, &ts);
    return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

std::string safe(const char* s) { return s != nullptr ? std::string(s) : std::string(); }

class AravisCamera final : public Camera {
public:
    AravisCamera(std::string device_id, GObjectPtr<ArvCamera> camera, AravisCameraOptions options)
        : m_label("aravis://" + device_id),
          m_camera(std::move(camera)),
          m_options(std::move(options)) {
        m_info.uri = m_label;
        ArvDevice* device = arv_camera_get_device(m_camera.get());
        m_genicam = arv_device_get_genicam(device);
        m_control_address = gige_control_address(device);
        // Aravis's heartbeat thread emits control-lost when the camera no longer grants us control.
        g_signal_connect(device, "control-lost", G_CALLBACK(+[](ArvDevice*, gpointer self) {
                             static_cast<AravisCamera*>(self)->m_control_lost = true;
                         }),
                         this);
    }

    ~AravisCamera() override {
        if (m_streaming) stop();
        g_signal_handlers_disconnect_by_data(arv_camera_get_device(m_camera.get()), this);
        if (m_gone) {
            // Closing a GigE camera that is gone blocks for seconds in Aravis (the stream's and the
            // device's goodbye writes time out, the heartbeat thread finishes a retry loop):
            // release both in the background so the error reaches the user now, not after that.
            std::thread([stream = m_stream.release(), camera = m_camera.release()] {
                if (stream != nullptr) g_object_unref(stream);
                g_object_unref(camera);
            }).detach();
        }
    }

    Status configure() {
        ArvCamera* cam = m_camera.get();
        GErrorSlot e;
        if (arv_camera_is_gv_device(cam) && m_options.auto_packet_size) {
            // Negotiates the largest GVSP packet the path carries (test packets of decreasing
            // size); Aravis keeps the camera's current size when the device cannot fire test
            // packets.
            arv_camera_gv_auto_packet_size(cam, e.out());
            if (e)
                return to_device_error(e.get(), m_label, "negotiating the GigE Vision packet size");
        }
        if (m_options.pixel_format) {
            if (Status s = set_pixel_format(*m_options.pixel_format); !s) return s;
        }
        if (m_options.width || m_options.height) {
            gint x = 0, y = 0, w = 0, h = 0;
            arv_camera_get_region(cam, &x, &y, &w, &h, e.out());
            if (e) return to_device_error(e.get(), m_label, "reading the region of interest");
            arv_camera_set_region(cam, 0, 0, m_options.width.value_or(w),
                                  m_options.height.value_or(h), e.out());
            if (e) return to_device_error(e.get(), m_label, "setting the region of interest");
        }
        if (m_options.frame_rate_hz) {
            if (Status s = set_frame_rate(*m_options.frame_rate_hz); !s) return s;
        }
        if (arv_camera_is_feature_available(cam, "TriggerMode", nullptr)) {
            if (m_options.software_trigger) {
                arv_camera_set_trigger(cam, "Software", e.out());
                if (e) return to_device_error(e.get(), m_label, "setting TriggerSource=Software");
            } else {
                arv_camera_clear_triggers(cam, e.out());
                if (e)
                    return to_device_error(e.get(), m_label,
                                           "switching triggers off (free running)");
            }
        } else if (m_options.software_trigger) {
            return DeviceError{DeviceErrorCode::NotSupported,
                               m_label + ": no TriggerMode feature for a software trigger"};
        }
        find_temperature_feature();
        return refresh_info();
    }

    CameraInfo info() const override { return m_info; }

    Status set_pixel_format(const std::string& format) override {
        if (m_streaming) return busy("set_pixel_format");
        if (find_pixel_format(format) == nullptr)
            return DeviceError{DeviceErrorCode::InvalidArgument,
                               fmt::format("{}: pixel format '{}' not handled; expected one of {}",
                                           m_label, format, supported_pixel_formats())};
        GErrorSlot e;
        if (!arv_camera_is_enumeration_entry_available(m_camera.get(), "PixelFormat",
                                                       format.c_str(), e.out())) {
            return DeviceError{
                DeviceErrorCode::NotSupported,
                fmt::format("{}: the camera does not offer pixel format '{}' (available: {})",
                            m_label, format, available_entries("PixelFormat"))};
        }
        arv_camera_set_pixel_format_from_string(m_camera.get(), format.c_str(), e.out());
        if (e) return to_device_error(e.get(), m_label, "setting PixelFormat=" + format);
        return refresh_info();
    }

    Status set_frame_rate(double hz) override {
        if (!(hz > 0.0) || !std::isfinite(hz))
            return DeviceError{DeviceErrorCode::InvalidArgument,
                               fmt::format("{}: frame rate {} Hz", m_label, hz)};
        ArvCamera* cam = m_camera.get();
        GErrorSlot e;
        for (const char* name : {"AcquisitionFrameRate", "AcquisitionFrameRateAbs"}) {
            ArvGcNode* node = arv_gc_get_node(m_genicam, name);
            if (node == nullptr || !ARV_IS_GC_FLOAT(node) || ARV_IS_GC_ENUMERATION(node)) continue;
            if (arv_camera_is_feature_available(cam, "AcquisitionFrameRateEnable", nullptr)) {
                arv_camera_set_boolean(cam, "AcquisitionFrameRateEnable", TRUE, e.out());
                if (e)
                    return to_device_error(e.get(), m_label,
                                           "setting AcquisitionFrameRateEnable=true");
            }
            auto* feature = ARV_GC_FLOAT(node);
            const double lo = arv_gc_float_get_min(feature, nullptr);
            const double hi = arv_gc_float_get_max(feature, nullptr);
            if (hz < lo || hz > hi)
                return DeviceError{
                    DeviceErrorCode::InvalidArgument,
                    fmt::format("{}: frame rate {} Hz outside {}'s range [{}, {}] Hz", m_label, hz,
                                name, lo, hi)};
            arv_gc_float_set_value(feature, hz, e.out());
            if (e) return to_device_error(e.get(), m_label, fmt::format("setting {}={}", name, hz));
            m_frame_rate_feature = name;
            return refresh_info();
        }
        for (const std::string& name : aravis_frame_rate_feature_names()) {
            ArvGcNode* node = arv_gc_get_node(m_genicam, name.c_str());
            if (node == nullptr || !ARV_IS_GC_ENUMERATION(node)) continue;
            return set_frame_rate_enum(name, hz);
        }
        return DeviceError{
            DeviceErrorCode::NotSupported,
            m_label +
                ": no frame-rate feature (probed AcquisitionFrameRate, AcquisitionFrameRateAbs, "
                "IRFrameRate, FrameRate)"};
    }

    Status start() override {
        if (m_streaming) return ok_status();
        ArvCamera* cam = m_camera.get();
        GErrorSlot e;
        // A session killed mid-stream leaves the camera acquiring towards its dead port; the fake
        // camera (and a camera that latches the destination at AcquisitionStart) keeps sending
        // there. Stopping first makes the acquisition below start towards this stream.
        arv_camera_stop_acquisition(cam, nullptr);
        arv_camera_set_acquisition_mode(cam, ARV_ACQUISITION_MODE_CONTINUOUS, e.out());
        if (e) return to_device_error(e.get(), m_label, "setting AcquisitionMode=Continuous");
        const guint payload = arv_camera_get_payload(cam, e.out());
        if (e) return to_device_error(e.get(), m_label, "reading PayloadSize");
        m_stream.reset(arv_camera_create_stream(cam, nullptr, nullptr, e.out()));
        if (e || !m_stream) return to_device_error(e.get(), m_label, "creating the stream");
        for (int i = 0; i < std::max(2, m_options.stream_buffers); ++i)
            arv_stream_push_buffer(m_stream.get(), arv_buffer_new_allocate(payload));
        m_ids.restart();
        m_pending_incomplete = 0;
        arv_camera_start_acquisition(cam, e.out());
        if (e) {
            m_stream.reset();
            return to_device_error(e.get(), m_label, "AcquisitionStart");
        }
        m_streaming = true;
        return ok_status();
    }

    Status stop() override {
        if (!m_streaming) return ok_status();
        m_streaming = false;
        GErrorSlot e;
        if (m_gone)
            return ok_status();  // nothing to tell a camera that is gone; released by the
                                 // destructor
        arv_camera_stop_acquisition(m_camera.get(), e.out());
        m_stream.reset();  // stops the stream thread and frees its buffers
        if (e) return to_device_error(e.get(), m_label, "AcquisitionStop");
        return ok_status();
    }

    Result<Frame> grab(std::chrono::milliseconds timeout) override {
        if (!m_streaming)
            return DeviceError{DeviceErrorCode::InvalidArgument,
                               m_label + ": grab() before start()"};
        if (m_options.software_trigger) {
            GErrorSlot e;
            arv_camera_software_trigger(m_camera.get(), e.out());
            if (e) return to_device_error(e.get(), m_label, "TriggerSoftware");
        }
        using Clock = std::chrono::steady_clock;
        const auto deadline = Clock::now() + timeout;
        auto last_sign_of_life = Clock::now();
        for (;;) {
            if (m_control_lost)
                return disconnected("Aravis's heartbeat reports the control channel lost");
            const auto now = Clock::now();
            if (now - last_sign_of_life >= kProbeAfterSilence) {
                if (auto lost = check_alive(); !lost.empty()) return disconnected(lost);
                last_sign_of_life = Clock::now();
            }
            const auto left = std::chrono::duration_cast<std::chrono::microseconds>(deadline - now);
            if (left.count() <= 0) break;
            // Short waits: a camera that vanished is noticed by the probe within about a second,
            // not after the whole frame timeout.
            const auto wait = std::min<std::chrono::microseconds>(left, kProbeAfterSilence);
            ArvBuffer* buffer =
                arv_stream_timeout_pop_buffer(m_stream.get(), static_cast<guint64>(wait.count()));
            if (buffer == nullptr) continue;
            last_sign_of_life = Clock::now();
            Frame frame;
            const bool complete = take(buffer, frame);
            arv_stream_push_buffer(m_stream.get(), buffer);
            if (complete) return frame;
        }
        return DeviceError{
            DeviceErrorCode::Timeout,
            fmt::format("{}: no complete frame within {} ms", m_label, timeout.count())};
    }

    StreamStatistics statistics() const override { return m_stats; }

    std::optional<double> device_temperature_k() override {
        if (!m_temperature_feature) return std::nullopt;
        auto* node = ARV_GC_FLOAT(arv_gc_get_node(m_genicam, m_temperature_feature->c_str()));
        GErrorSlot e;
        const double value = arv_gc_float_get_value(node, e.out());
        if (e) return std::nullopt;
        return m_temperature_in_kelvin ? value : value + kZeroCelsiusK;
    }

private:
    /// The GVCP address of a GigE Vision camera (nullopt for USB3 Vision and others).
    static std::optional<sockaddr_in> gige_control_address(ArvDevice* device) {
        if (!ARV_IS_GV_DEVICE(device)) return std::nullopt;
        GSocketAddress* address = arv_gv_device_get_device_address(ARV_GV_DEVICE(device));
        sockaddr_in native{};
        if (address == nullptr ||
            !g_socket_address_to_native(address, &native, sizeof native, nullptr))
            return std::nullopt;
        return native;
    }

    /// Empty while the camera answers on its control channel, else what shows it is gone.
    std::string check_alive() const {
        if (!m_control_address) return {};
        switch (gvcp::probe_register(*m_control_address, gvcp::kVersionRegister, kProbeTimeout,
                                     kProbeTries)) {
            case gvcp::ProbeResult::Answered:
                return {};
            case gvcp::ProbeResult::Refused:
                return "its control port refuses a register read (ICMP port unreachable: the "
                       "device or the program "
                       "serving it is gone)";
            case gvcp::ProbeResult::Silent:
                return fmt::format(
                    "it answers no register read on its control channel ({} tries of {} ms)",
                    kProbeTries, kProbeTimeout.count());
        }
        return {};
    }

    DeviceError disconnected(const std::string& why) {
        m_gone = true;
        return {DeviceErrorCode::Disconnected,
                fmt::format("{}: no frame for {} ms and {}; the camera is disconnected (cable, "
                            "power or network?)",
                            m_label, kProbeAfterSilence.count(), why)};
    }

    DeviceError busy(const char* what) const {
        return {DeviceErrorCode::InvalidArgument,
                fmt::format("{}: {} while streaming; stop() first", m_label, what)};
    }

    std::string available_entries(const char* feature) const {
        guint n = 0;
        std::unique_ptr<const char*, aravis::GFree> entries(
            arv_camera_dup_available_enumerations_as_strings(m_camera.get(), feature, &n, nullptr));
        std::vector<std::string> names;
        for (guint i = 0; entries && i < n; ++i) names.emplace_back(entries.get()[i]);
        return fmt::format("{}", fmt::join(names, ", "));
    }

    Status set_frame_rate_enum(const std::string& feature, double hz) {
        guint n = 0;
        GErrorSlot e;
        std::unique_ptr<const char*, aravis::GFree> entries(
            arv_camera_dup_available_enumerations_as_strings(m_camera.get(), feature.c_str(), &n,
                                                             e.out()));
        if (e) return to_device_error(e.get(), m_label, "listing " + feature + " entries");
        std::string best;
        double best_error = 0.0;
        for (guint i = 0; i < n; ++i) {
            const auto rate = frame_rate_from_entry_name(entries.get()[i]);
            if (!rate) continue;
            const double error = std::abs(*rate - hz) / hz;
            if (best.empty() || error < best_error) {
                best = entries.get()[i];
                best_error = error;
            }
        }
        // Thermal cores offer a few fixed rates: choose one only when it is the rate asked for (±1
        // %), never silently another.
        if (best.empty() || best_error > 0.01)
            return DeviceError{
                DeviceErrorCode::InvalidArgument,
                fmt::format("{}: {} Hz is not one of the rates of enumeration {} ({})", m_label, hz,
                            feature, available_entries(feature.c_str()))};
        arv_camera_set_string(m_camera.get(), feature.c_str(), best.c_str(), e.out());
        if (e)
            return to_device_error(e.get(), m_label, fmt::format("setting {}={}", feature, best));
        m_frame_rate_feature = feature;
        return refresh_info();
    }

    std::optional<double> current_frame_rate() const {
        std::vector<std::string> names;
        if (m_frame_rate_feature) names.push_back(*m_frame_rate_feature);
        for (const auto& n : aravis_frame_rate_feature_names()) names.push_back(n);
        for (const auto& name : names) {
            ArvGcNode* node = arv_gc_get_node(m_genicam, name.c_str());
            if (node == nullptr) continue;
            GErrorSlot e;
            if (ARV_IS_GC_ENUMERATION(node)) {
                const char* entry =
                    arv_gc_enumeration_get_string_value(ARV_GC_ENUMERATION(node), e.out());
                if (!e && entry != nullptr) return frame_rate_from_entry_name(entry);
            } else if (ARV_IS_GC_FLOAT(node)) {
                const double v = arv_gc_float_get_value(ARV_GC_FLOAT(node), e.out());
                if (!e) return v;
            }
        }
        return std::nullopt;
    }

    void find_temperature_feature() {
        for (const char* name : kTemperatureFeatures) {
            ArvGcNode* node = arv_gc_get_node(m_genicam, name);
            if (node == nullptr || !ARV_IS_GC_FLOAT(node)) continue;
            // SFNC defines DeviceTemperature in degrees Celsius; a node declaring <Unit>K</Unit> is
            // kelvin.
            const std::string unit = safe(arv_gc_float_get_unit(ARV_GC_FLOAT(node)));
            m_temperature_in_kelvin = unit == "K" || unit == "Kelvin";
            m_temperature_feature = name;
            return;
        }
    }

    Status refresh_info() {
        ArvCamera* cam = m_camera.get();
        GErrorSlot e;
        m_info.vendor = safe(arv_camera_get_vendor_name(cam, nullptr));
        m_info.model = safe(arv_camera_get_model_name(cam, nullptr));
        m_info.serial = safe(arv_camera_get_device_serial_number(cam, nullptr));
        gint x = 0, y = 0;
        arv_camera_get_region(cam, &x, &y, &m_info.width, &m_info.height, e.out());
        if (e) return to_device_error(e.get(), m_label, "reading Width/Height");
        const ArvPixelFormat format = arv_camera_get_pixel_format(cam, e.out());
        if (e) return to_device_error(e.get(), m_label, "reading PixelFormat");
        m_info.pixel_format = safe(arv_camera_get_pixel_format_as_string(cam, nullptr));
        // PFNC: bits 16–23 of the pixel format code are the bits a pixel occupies; the significant
        // bits are in the name (Mono14 → 14).
        m_info.bits_per_pixel = static_cast<int>(ARV_PIXEL_FORMAT_BIT_PER_PIXEL(format));
        const GenICamPixelFormat* known = find_pixel_format(static_cast<std::uint32_t>(format));
        if (known != nullptr) m_info.bits_per_pixel = known->significant_bits;
        m_info.microgrid_pattern_deg = m_options.microgrid_pattern_deg;
        if (known != nullptr && known->polarized && !m_info.microgrid_pattern_deg)
            m_info.microgrid_pattern_deg = kSonyPolarizedLayoutDeg;
        m_info.frame_rate_hz = current_frame_rate();
        m_info.planck_constants.clear();
        for (const char* constant : kPlanckFeatures) {
            ArvGcNode* node = arv_gc_get_node(m_genicam, constant);
            if (node == nullptr) continue;
            GErrorSlot read_error;
            double value = 0.0;
            if (ARV_IS_GC_FLOAT(node))
                value = arv_gc_float_get_value(ARV_GC_FLOAT(node), read_error.out());
            else if (ARV_IS_GC_INTEGER(node))
                value = static_cast<double>(
                    arv_gc_integer_get_value(ARV_GC_INTEGER(node), read_error.out()));
            else
                continue;
            if (!read_error) m_info.planck_constants[constant] = value;
        }
        return ok_status();
    }

    /// Fills `frame` from `buffer` when it holds a complete image; counts ids, losses and damage.
    /// Only complete frames feed the id unwrapper: Aravis 0.8.26 sets a buffer's frame id from the
    /// GVSP leader, so a frame whose leader was lost is popped as MISSING_PACKETS still carrying
    /// the id of the buffer's previous use (or 0) — seen on the fake camera with -r. Damaged
    /// buffers are counted as incomplete and absorbed by the next id gap; the rest of the gap was
    /// never received (dropped).
    bool take(ArvBuffer* buffer, Frame& frame) {
        if (arv_buffer_get_status(buffer) != ARV_BUFFER_STATUS_SUCCESS ||
            arv_buffer_get_payload_type(buffer) != ARV_BUFFER_PAYLOAD_TYPE_IMAGE) {
            damaged();
            return false;
        }
        const ArvPixelFormat code = arv_buffer_get_image_pixel_format(buffer);
        const auto bits = ARV_PIXEL_FORMAT_BIT_PER_PIXEL(code);
        const GenICamPixelFormat* format = find_pixel_format(static_cast<std::uint32_t>(code));
        const int stored_bits = format != nullptr ? format->stored_bits : static_cast<int>(bits);
        if (stored_bits != 8 && stored_bits != 12 && stored_bits != 16) {
            damaged();
            return false;
        }
        frame.width = arv_buffer_get_image_width(buffer);
        frame.height = arv_buffer_get_image_height(buffer);
        if (frame.width <= 0 || frame.height <= 0) {
            damaged();
            return false;
        }
        gint x_padding = 0, y_padding = 0;
        arv_buffer_get_image_padding(buffer, &x_padding, &y_padding);
        const std::size_t row =
            (static_cast<std::size_t>(frame.width) * static_cast<std::size_t>(stored_bits) + 7) / 8;
        const auto stride = row + static_cast<std::size_t>(x_padding);
        size_t size = 0;
        const auto* data =
            static_cast<const std::uint8_t*>(arv_buffer_get_image_data(buffer, &size));
        const std::size_t needed = stride * static_cast<std::size_t>(frame.height - 1) + row;
        if (data == nullptr || size < needed) {
            damaged();
            return false;
        }
        const FrameIdStep step = m_ids.next(arv_buffer_get_frame_id(buffer));
        if (step.duplicate) return false;
        const std::uint64_t absorbed = std::min(m_pending_incomplete, step.missed);
        m_pending_incomplete -= absorbed;
        m_stats.dropped += step.missed - absorbed;
        frame.frame_id = step.id;
        if (stored_bits == 12)
            decode_mono12p(data, frame.width, frame.height, stride, frame.counts);
        else
            decode_mono(data, frame.width, frame.height, stored_bits / 8, stride, frame.counts);
        frame.device_timestamp_ns = static_cast<std::int64_t>(arv_buffer_get_timestamp(buffer));
        const auto system_ns = static_cast<std::int64_t>(arv_buffer_get_system_timestamp(buffer));
        frame.host_timestamp_ns = system_ns != 0 ? system_ns : realtime_now_ns();
        frame.fpa_temperature_k = cached_temperature();
        ++m_stats.delivered;
        return true;
    }

    void damaged() {
        ++m_stats.incomplete;
        ++m_pending_incomplete;
    }

    /// A register read costs a control round trip; re-read the temperature at most once a second.
    std::optional<double> cached_temperature() {
        if (!m_temperature_feature) return std::nullopt;
        const auto now = std::chrono::steady_clock::now();
        if (!m_temperature_read || now - m_temperature_time > std::chrono::seconds(1)) {
            m_temperature_k = device_temperature_k();
            m_temperature_time = now;
            m_temperature_read = true;
        }
        return m_temperature_k;
    }

    /// Without a frame for this long, ask the camera whether it is still there.
    static constexpr std::chrono::milliseconds kProbeAfterSilence{500};
    static constexpr std::chrono::milliseconds kProbeTimeout{200};
    static constexpr int kProbeTries = 3;

    std::string m_label;
    GObjectPtr<ArvCamera> m_camera;
    std::optional<sockaddr_in> m_control_address;
    std::atomic<bool> m_control_lost{false};
    bool m_gone = false;  ///< grab() found the camera disconnected
    GObjectPtr<ArvStream> m_stream;
    ArvGc* m_genicam = nullptr;  ///< owned by the device
    AravisCameraOptions m_options;
    CameraInfo m_info;
    bool m_streaming = false;
    FrameIdUnwrapper m_ids = FrameIdUnwrapper::gige_vision_16bit();
    StreamStatistics m_stats;
    std::uint64_t m_pending_incomplete = 0;  ///< damaged frames not yet matched to an id gap
    std::optional<std::string> m_frame_rate_feature;
    std::optional<std::string> m_temperature_feature;
    bool m_temperature_in_kelvin = false;
    bool m_temperature_read = false;
    std::optional<double> m_temperature_k;
    std::chrono::steady_clock::time_point m_temperature_time;
};

}  // namespace

const std::vector<std::string>& aravis_frame_rate_feature_names() {
    static const std::vector<std::string> names = {
        "AcquisitionFrameRate", "AcquisitionFrameRateAbs", "IRFrameRate", "FrameRate"};
    return names;
}

std::optional<double> frame_rate_from_entry_name(const std::string& entry) {
    std::size_t i = 0;
    while (i < entry.size() && !std::isdigit(static_cast<unsigned char>(entry[i]))) ++i;
    if (i == entry.size()) return std::nullopt;
    std::string number;
    for (; i < entry.size(); ++i) {
        const char c = entry[i];
        if (std::isdigit(static_cast<unsigned char>(c))) {
            number += c;
        } else if ((c == '_' || c == 'p' || c == '.') && i + 1 < entry.size() &&
                   std::isdigit(static_cast<unsigned char>(entry[i + 1])) &&
                   number.find('.') == std::string::npos) {
            number += '.';
        } else {
            break;
        }
    }
    return std::stod(number);
}

namespace {
bool listed(const std::string& device_id) {
    const unsigned n = arv_get_n_devices();
    for (unsigned i = 0; i < n; ++i)
        if (safe(arv_get_device_id(i)) == device_id) return true;
    return false;
}
}  // namespace

std::vector<AravisDeviceInfo> discover_aravis_cameras() {
    arv_update_device_list();
    std::vector<AravisDeviceInfo> devices;
    const unsigned n = arv_get_n_devices();
    for (unsigned i = 0; i < n; ++i) {
        devices.push_back({safe(arv_get_device_id(i)), safe(arv_get_device_vendor(i)),
                           safe(arv_get_device_model(i)), safe(arv_get_device_serial_nbr(i)),
                           safe(arv_get_device_address(i)), safe(arv_get_device_protocol(i))});
    }
    return devices;
}

namespace {

/// GigE Vision bootstrap register "Heartbeat timeout" (ms), readable without control privilege.
constexpr guint64 kHeartbeatTimeoutRegister = 0x0938;

struct OpenAttempt {
    Result<std::unique_ptr<Camera>> camera;
    bool retry = false;  ///< failed because an earlier control session still holds the camera
    std::optional<guint32> heartbeat_timeout_ms;
};

OpenAttempt open_once(const std::string& device_id, const AravisCameraOptions& options) {
    const std::string label = "aravis://" + device_id;
    GErrorSlot e;
    GObjectPtr<ArvCamera> camera(arv_camera_new(device_id.c_str(), e.out()));
    if (e || !camera)
        return {to_device_error(e.get(), label, "opening the camera"), false, std::nullopt};
    ArvDevice* device = arv_camera_get_device(camera.get());
    if (ARV_IS_GV_DEVICE(device) && !arv_gv_device_is_controller(ARV_GV_DEVICE(device))) {
        // Aravis opens the camera even when its request for control privilege goes unanswered;
        // every later write would then time out and the stream be refused.
        guint32 heartbeat_ms = 0;
        const bool read =
            arv_device_read_register(device, kHeartbeatTimeoutRegister, &heartbeat_ms, nullptr);
        return {
            DeviceError{
                DeviceErrorCode::DeviceFault,
                label +
                    ": Controller privilege required: another control session holds the camera"},
            true, read ? std::optional<guint32>(heartbeat_ms) : std::nullopt};
    }
    auto result = std::make_unique<AravisCamera>(device_id, std::move(camera), options);
    if (Status s = result->configure(); !s)
        // A timeout here means our writes were ignored: control was lost again.
        return {s.error(), s.error().code == DeviceErrorCode::Timeout, std::nullopt};
    return {std::unique_ptr<Camera>(std::move(result)), false, std::nullopt};
}

}  // namespace

Result<std::unique_ptr<Camera>> open_aravis_camera(const std::string& device_id,
                                                   const AravisCameraOptions& options) {
    // Observed with Aravis 0.8.26 and the fake camera on 127.0.0.1: opening a GigE Vision camera by
    // id when the id is not yet in Aravis's device list (no arv_update_device_list() in this
    // process) gives a camera that opens but never streams; opened after a list update (or by IP
    // address), it streams. So refresh the list first unless the id is an address or already
    // listed.
    in_addr address{};
    if (inet_pton(AF_INET, device_id.c_str(), &address) != 1 && !listed(device_id))
        arv_update_device_list();
    // A GigE Vision camera grants control to one host session at a time and frees it only when that
    // session's heartbeat times out: right after a session was killed (kill -9, a crash, a pulled
    // cable) the camera refuses a new one for up to its heartbeat timeout. Retry with a growing
    // pause instead of asking the user to try again.
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    auto pause = std::chrono::milliseconds(250);
    for (int attempt = 1;; ++attempt) {
        OpenAttempt a = open_once(device_id, options);
        if (a.camera.ok() || !a.retry) {
            if (a.camera.ok() && attempt > 1)
                spdlog::info("aravis://{}: control privilege obtained after {} attempts ({:.1f} s)",
                             device_id, attempt,
                             std::chrono::duration<double>(Clock::now() - start).count());
            return std::move(a.camera);
        }
        const auto elapsed = Clock::now() - start;
        if (elapsed + pause > options.control_wait) {
            DeviceError error = a.camera.error();
            error.message += fmt::format(
                "; still refused after {:.1f} s and {} attempts: another program (arv-viewer, a "
                "second tirpol) "
                "controls it",
                std::chrono::duration<double>(elapsed).count(), attempt);
            return error;
        }
        if (attempt == 1)
            spdlog::warn(
                "aravis://{}: the camera is still held by an earlier control session (a program "
                "that crashed or was "
                "killed keeps it until its heartbeat times out{}); retrying for up to {:.0f} s",
                device_id,
                a.heartbeat_timeout_ms
                    ? fmt::format(", {} ms on this camera", *a.heartbeat_timeout_ms)
                    : std::string(),
                std::chrono::duration<double>(options.control_wait).count());
        std::this_thread::sleep_for(pause);
        pause = std::min(pause * 2, std::chrono::milliseconds(2000));
    }
}

}  // namespace tirpol::acquisition
