#include "live_view.h"

#include <fmt/format.h>

#include <cmath>

#include "snapshot.h"
#include "tirpol/acquisition/camera.h"
#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/stage.h"
#include "tirpol/calibration/microgrid_stokes.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/utc_time.h"

namespace tirpol::live {

using namespace acquisition;

namespace {
/// The last FPA samples sent with each status (the page plots them; one a second → 10 minutes).
constexpr std::size_t kFpaSamplesInStatus = 600;

DisplayImage stokes_image(const Image& stokes, const std::string& signal_units) {
    DisplayImage image;
    image.width = stokes.width();
    image.height = stokes.height();
    for (const char* name : {"S0", "S1", "S2", "DoLP", "AoP"}) {
        const std::string n = name;
        image.channels.push_back({n,
                                  n == "DoLP"  ? ""
                                  : n == "AoP" ? "deg"
                                               : signal_units,
                                  stokes.channel(n),
                                  {}});
    }
    if (const auto angles =
            read_stokes_image_header(stokes, "live Stokes image").analyzer_angles_deg)
        image.info["analyzer_angles_deg"] = *angles;
    return image;
}
}  // namespace

void validate(const LiveViewOptions& options) {
    if (options.camera_uri.empty()) fail("--camera: expected a camera URI");
    const CycleOptions& c = options.cycle;
    if (c.frames_per_angle < 1)
        fail("--frames-per-angle: expected an integer ≥ 1, got {}", c.frames_per_angle);
    if (!std::isfinite(c.settle_s) || c.settle_s < 0.0)
        fail("--settle-s: expected a finite number of seconds ≥ 0, got {}", c.settle_s);
    for (const auto& [name, seconds] :
         {std::pair{"move timeout", c.move_timeout_s}, std::pair{"home timeout", c.home_timeout_s},
          std::pair{"frame timeout", c.frame_timeout_s}})
        if (!std::isfinite(seconds) || seconds <= 0.0)
            fail("live view: the {} must be a finite number of seconds > 0, got {}", name, seconds);
    calibration::parse_demosaic_method(options.demosaic, "--demosaic");
    for (const double angle_deg : c.angles_deg)
        if (!std::isfinite(angle_deg))
            fail("live view: polarizer angle {} is not a finite number of degrees", angle_deg);
}

LiveView::LiveView(const LiveViewOptions& options) : m_options(options) {
    validate(options);
    m_camera = open_camera(options.camera_uri).value_or_throw();
    if (!options.stage_uri.empty())
        m_stage =
            couple_simulated_polarizer(*m_camera, open_stage(options.stage_uri).value_or_throw());
    if (!options.calibration_path.empty())
        m_calibration = calibration::read_radiometric_calibration(options.calibration_path);
    m_converter = std::make_unique<DisplayConverter>(
        m_camera->info(), m_calibration ? &*m_calibration : nullptr, options.unit);
    m_feed = std::make_unique<FrameFeed>(*m_camera);
    if (!m_stage && m_camera->info().microgrid_pattern_deg) {
        m_microgrid.emplace(*m_camera->info().microgrid_pattern_deg, "the camera's microgrid");
        m_demosaic = calibration::parse_demosaic_method(options.demosaic, "--demosaic");
    }
    if (m_stage) {
        m_cycle = std::make_unique<PolarizerCycle>(*m_feed, *m_stage, *m_converter, options.cycle);
        m_capture = std::make_unique<CaptureControl>(*m_feed, *m_stage, m_cycle.get());
    }
    std::move(m_feed->start()).value_or_throw();
    if (m_cycle) m_cycle->start();
}

LiveView::~LiveView() {
    m_capture.reset();
    if (m_cycle) m_cycle->stop();
    m_feed->stop();
}

CaptureControl& LiveView::capture() {
    if (!m_capture) fail("live view: capturing a plan needs a stage (--stage URI)");
    return *m_capture;
}

template <typename T, typename Encode>
EncodedImage LiveView::encoded_after(const LatestSlot<T>& slot, Cache& cache, std::uint64_t after,
                                     std::chrono::milliseconds timeout, Encode encode) {
    const auto snapshot = slot.wait_newer(after, timeout);
    if (snapshot.sequence <= after || !snapshot.value) return {snapshot.sequence, nullptr};
    std::lock_guard lock(cache.mutex);
    if (cache.image.sequence != snapshot.sequence)
        cache.image = {snapshot.sequence,
                       std::make_shared<const std::string>(encode(*snapshot.value))};
    return cache.image;
}

EncodedImage LiveView::frame_after(std::uint64_t after, std::chrono::milliseconds timeout) {
    return encoded_after(m_feed->latest(), m_frame_cache, after, timeout, [&](const Frame& frame) {
        try {
            return encode_display_image(m_converter->frame_image(frame));
        } catch (const Error&
                     e) {  // e.g. an FPA-dependent calibration and a frame without FPA temperature
            DisplayImage image;
            image.info["error"] = e.what();
            return encode_display_image(image);
        }
    });
}

Image LiveView::microgrid_stokes(const Frame& frame) const {
    calibration::MicrogridReductionOptions options;
    options.method = m_demosaic;
    options.reduction.units = m_converter->unit() == DisplayUnit::Counts ? "counts" : "W/(m^2 sr)";
    options.source = fmt::format("frame {}", frame.frame_id);
    Image stokes =
        calibration::reduce_microgrid(m_converter->to_signal(frame.counts, frame.fpa_temperature_k),
                                      frame.width, frame.height, *m_microgrid, options);
    stokes.attributes()["microgrid_frame_id"] = std::to_string(frame.frame_id);
    return stokes;
}

std::shared_ptr<const Image> LiveView::latest_stokes() const {
    if (m_cycle) return m_cycle->stokes().latest().value;
    if (m_microgrid)
        if (const auto frame = m_feed->latest().latest().value)
            return std::make_shared<const Image>(microgrid_stokes(*frame));
    return nullptr;
}

EncodedImage LiveView::stokes_after(std::uint64_t after, std::chrono::milliseconds timeout) {
    const std::string units = m_converter->unit() == DisplayUnit::Counts ? "counts" : "W/(m²·sr)";
    if (m_microgrid)  // every frame the page asks for, demosaiced once however many pages ask
        return encoded_after(
            m_feed->latest(), m_stokes_cache, after, timeout, [&](const Frame& frame) {
                try {
                    return encode_display_image(stokes_image(microgrid_stokes(frame), units));
                } catch (const Error& e) {
                    DisplayImage image;
                    image.info["error"] = e.what();
                    return encode_display_image(image);
                }
            });
    if (!m_cycle) return {};
    return encoded_after(
        m_cycle->stokes(), m_stokes_cache, after, timeout,
        [&](const Image& stokes) { return encode_display_image(stokes_image(stokes, units)); });
}

nlohmann::json LiveView::region(const PixelRegion& region, double dolp_min) const {
    const auto frame = m_feed->latest().latest().value;
    if (!frame) fail("region: no frame from the camera yet");
    const DisplayImage live = m_converter->frame_image(*frame);
    std::optional<DisplayImage> cycle;
    if (const auto stokes = latest_stokes();
        stokes && stokes->width() == live.width && stokes->height() == live.height)
        cycle = stokes_image(*stokes,
                             m_converter->unit() == DisplayUnit::Counts ? "counts" : "W/(m²·sr)");
    return region_readout(&live, cycle ? &*cycle : nullptr, region, dolp_min);
}

nlohmann::json LiveView::snapshot() {
    if (m_options.snapshot_dir.empty())
        fail("snapshot: tirpol live was started without --snapshot-dir FOLDER");
    const auto frame = m_feed->latest().latest().value;
    if (!frame) fail("snapshot: no frame from the camera yet");
    // A microgrid snapshot reduces the very frame it stores as live_S0.
    const std::shared_ptr<const Image> cycle =
        m_microgrid ? std::make_shared<const Image>(microgrid_stokes(*frame)) : latest_stokes();
    if (cycle && (cycle->width() != frame->width || cycle->height() != frame->height))
        fail(
            "snapshot: the Stokes images ({}×{}, super-pixel) and the frame ({}×{}) differ in "
            "size; use --demosaic bilinear or newton for snapshots",
            cycle->width(), cycle->height(), frame->width, frame->height);
    const std::string units = m_converter->unit() == DisplayUnit::Counts ? "counts" : "W/(m²·sr)";
    Image image = cycle ? *cycle : Image(frame->width, frame->height);
    image.set_channel(cycle ? "live_S0" : "S0",
                      m_converter->to_signal(frame->counts, frame->fpa_temperature_k));
    auto& a = image.attributes();
    const std::string time = utc_now_iso8601();
    a["time_utc"] = time;
    const CameraInfo& c = m_feed->camera_info();
    a["camera_uri"] = c.uri;
    a["camera_vendor"] = c.vendor;
    a["camera_model"] = c.model;
    a["camera_serial"] = c.serial;
    a["pixel_format"] = c.pixel_format;
    a["frame_id"] = std::to_string(frame->frame_id);  // 64 bits: an EXR int holds 32
    write_stokes_image_header(image,
                              {.units = units, .fpa_temperature_k = frame->fpa_temperature_k});
    if (m_stage) a["stage_uri"] = m_stage->info().uri;

    std::lock_guard lock(m_snapshot_mutex);
    std::string stem = "snapshot-" + time + "-" + std::to_string(++m_snapshots);
    for (char& ch : stem)
        if (ch == ':') ch = '-';  // file names without ':' (Windows shares, URLs)
    const SnapshotFiles files =
        write_snapshot(m_options.snapshot_dir, stem, image, units, m_options.force_snapshots);
    nlohmann::json j;
    j["folder"] = m_options.snapshot_dir;
    j["files"] = nlohmann::json::array({files.exr});
    for (const auto& png : files.pngs) j["files"].push_back(png);
    j["time_utc"] = time;
    j["frame_id"] = frame->frame_id;
    j["channels"] = image.channel_names();
    return j;
}

nlohmann::json LiveView::describe() const {
    const CameraInfo& c = m_feed->camera_info();
    nlohmann::json j;
    j["camera"] = {{"uri", c.uri},     {"vendor", c.vendor}, {"model", c.model},
                   {"width", c.width}, {"height", c.height}, {"pixel_format", c.pixel_format}};
    j["camera"]["frame_rate_hz"] =
        c.frame_rate_hz ? nlohmann::json(*c.frame_rate_hz) : nlohmann::json();
    j["units"] = m_converter->units();
    j["saturation_counts"] = m_converter->saturation_counts()
                                 ? nlohmann::json(*m_converter->saturation_counts())
                                 : nlohmann::json();
    j["calibration"] = m_options.calibration_path;
    j["stage"] = m_stage ? nlohmann::json(m_stage->info().uri) : nlohmann::json();
    j["angles_deg"] = m_options.cycle.angles_deg;
    j["default_plan"] = m_options.default_plan;
    j["default_output"] = m_options.default_output;
    j["snapshot_dir"] = m_options.snapshot_dir;
    j["microgrid"] =
        m_microgrid ? nlohmann::json({{"pattern", m_microgrid->text()},
                                      {"demosaic", calibration::demosaic_method_name(m_demosaic)}})
                    : nlohmann::json();
    return j;
}

nlohmann::json LiveView::status() const {
    const FeedStatistics s = m_feed->statistics();
    nlohmann::json j;
    j["camera"] = {{"delivered", s.delivered},
                   {"dropped", s.dropped},
                   {"incomplete", s.incomplete},
                   {"grabbed", s.grabbed},
                   {"error", s.last_error}};
    j["camera"]["frame_rate_hz"] =
        s.frame_rate_hz ? nlohmann::json(*s.frame_rate_hz) : nlohmann::json();
    if (const auto latest = m_feed->latest().latest().value) {
        j["camera"]["frame_id"] = latest->frame_id;
        j["camera"]["device_timestamp_ns"] = latest->device_timestamp_ns;
    }
    auto fpa = nlohmann::json::array();
    const auto history = m_feed->fpa_history();
    for (std::size_t i = history.size() > kFpaSamplesInStatus ? history.size() - kFpaSamplesInStatus
                                                              : 0;
         i < history.size(); ++i)
        fpa.push_back({history[i].time_s, history[i].temperature_k});
    j["fpa_temperature_k"] = std::move(fpa);
    if (m_cycle) {
        const CycleStatus c = m_cycle->status();
        j["stage"] = {{"state", c.state}, {"cycles", c.cycles}, {"error", c.error}};
        j["stage"]["angle_deg"] = c.angle_deg ? nlohmann::json(*c.angle_deg) : nlohmann::json();
    }
    if (m_capture) {
        const CaptureState c = m_capture->state();
        j["capture"] = {{"phase", to_string(c.phase)},
                        {"steps_total", c.steps_total},
                        {"steps_recorded", c.steps_recorded},
                        {"output", c.output},
                        {"message", c.message}};
    }
    return j;
}

}  // namespace tirpol::live
