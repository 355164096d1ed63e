#include "tirpol/acquisition/internal/lepton_frame.h"

#include <fmt/format.h>

#include <cmath>

namespace tirpol::acquisition {

std::optional<LeptonFrameLayout> lepton_telemetry_layout(int width, int height) {
    if (width == 80 && height == 63) return LeptonFrameLayout{80, 60, 3};
    if (width == 160 && height == 122) return LeptonFrameLayout{160, 120, 2};
    return std::nullopt;
}

std::optional<std::vector<std::uint16_t>> split_lepton_telemetry(Frame& frame,
                                                                 LeptonTelemetryLocation location) {
    const auto layout = lepton_telemetry_layout(frame.width, frame.height);
    if (!layout || frame.counts.size() != static_cast<std::size_t>(frame.width) *
                                              static_cast<std::size_t>(frame.height))
        return std::nullopt;
    const std::size_t telemetry_words =
        static_cast<std::size_t>(layout->telemetry_rows) * static_cast<std::size_t>(frame.width);
    const std::size_t image_words = frame.counts.size() - telemetry_words;
    const auto first_telemetry =
        location == LeptonTelemetryLocation::Footer
            ? frame.counts.begin() + static_cast<std::ptrdiff_t>(image_words)
            : frame.counts.begin();
    std::vector<std::uint16_t> words;
    words.reserve(telemetry_words);
    for (auto it = first_telemetry;
         it != first_telemetry + static_cast<std::ptrdiff_t>(telemetry_words); ++it)
        words.push_back(static_cast<std::uint16_t>(std::lround(*it)));
    frame.counts.erase(first_telemetry,
                       first_telemetry + static_cast<std::ptrdiff_t>(telemetry_words));
    frame.height = layout->image_height;
    return words;
}

void apply_lepton_telemetry(const lepton::Telemetry& t, Frame& frame) {
    frame.fpa_temperature_k = t.fpa_temperature_k;
    frame.telemetry =
        FrameTelemetry{t.frame_counter, t.ffc_state(), t.uptime_ms, t.uptime_at_last_ffc_ms};
}

namespace {

class LeptonTelemetryCamera final : public Camera {
public:
    LeptonTelemetryCamera(std::unique_ptr<Camera> inner, LeptonTelemetryLocation location,
                          LeptonFrameLayout layout)
        : m_inner(std::move(inner)), m_location(location), m_layout(layout) {}

    CameraInfo info() const override {
        CameraInfo i = m_inner->info();
        i.width = m_layout.image_width;
        i.height = m_layout.image_height;
        return i;
    }
    Status set_pixel_format(const std::string& format) override {
        return m_inner->set_pixel_format(format);
    }
    Status set_frame_rate(double hz) override { return m_inner->set_frame_rate(hz); }
    Status start() override { return m_inner->start(); }
    Status stop() override { return m_inner->stop(); }
    StreamStatistics statistics() const override { return m_inner->statistics(); }
    std::optional<double> device_temperature_k() override {
        return m_inner->device_temperature_k();
    }

    Result<Frame> grab(std::chrono::milliseconds timeout) override {
        auto grabbed = m_inner->grab(timeout);
        if (!grabbed) return grabbed.error();
        Frame frame = std::move(grabbed.value());
        const auto words = split_lepton_telemetry(frame, m_location);
        if (!words)
            return DeviceError{
                DeviceErrorCode::BadReply,
                fmt::format("{}: frame {} is {}×{}, expected {}×{} with the "
                            "Lepton's telemetry rows",
                            m_inner->info().uri, frame.frame_id, frame.width, frame.height,
                            m_layout.image_width, m_layout.image_height + m_layout.telemetry_rows)};
        const auto row_a = std::span(*words).first(lepton::kTelemetryRowWords);
        const auto telemetry = lepton::parse_telemetry(row_a);
        if (!telemetry)
            return DeviceError{
                DeviceErrorCode::BadReply,
                fmt::format("{}: frame {}: the telemetry row A at the {} has revision 0 (no "
                            "telemetry there: is telemetry enabled on the Lepton, at the {}?)",
                            m_inner->info().uri, frame.frame_id, location_name(), location_name())};
        apply_lepton_telemetry(*telemetry, frame);
        return frame;
    }

private:
    const char* location_name() const {
        return m_location == LeptonTelemetryLocation::Footer ? "footer" : "header";
    }

    std::unique_ptr<Camera> m_inner;
    LeptonTelemetryLocation m_location;
    LeptonFrameLayout m_layout;
};

}  // namespace

Result<std::unique_ptr<Camera>> wrap_lepton_telemetry_camera(std::unique_ptr<Camera> inner,
                                                             LeptonTelemetryLocation location) {
    const CameraInfo i = inner->info();
    const auto layout = lepton_telemetry_layout(i.width, i.height);
    if (!layout)
        return DeviceError{DeviceErrorCode::NotSupported,
                           fmt::format("{}: frames of {}×{} carry no Lepton telemetry rows "
                                       "(expected 80×63 for a Lepton 2.x or 160×122 for a "
                                       "Lepton 3.x: enable telemetry on the core, e.g. with "
                                       "--camera-control lepton://...)",
                                       i.uri, i.width, i.height)};
    if (i.bits_per_pixel != 16)
        return DeviceError{DeviceErrorCode::NotSupported,
                           fmt::format("{}: telemetry rows need 16-bit frames (format=Y16), the "
                                       "camera delivers {}",
                                       i.uri, i.pixel_format)};
    return std::unique_ptr<Camera>(
        std::make_unique<LeptonTelemetryCamera>(std::move(inner), location, *layout));
}

}  // namespace tirpol::acquisition
