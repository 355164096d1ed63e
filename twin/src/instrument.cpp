// The twin's instrument: world state, the sensor model as the camera's detector, and the devices.

#include "tirpol/twin/instrument.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <deque>
#include <thread>

#include "tirpol/acquisition/camera.h"
#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/frame_gate.h"  // host_realtime_ns
#include "tirpol/acquisition/sim/fake_gige_server.h"
#include "tirpol/acquisition/sim/simulated_camera.h"
#include "tirpol/acquisition/sim/stage_simulator.h"
#include "tirpol/acquisition/stage.h"
#include "tirpol/core/error.h"
#include "tirpol/core/geometry.h"
#include "tirpol/core/log.h"
#include "tirpol/core/session.h"

namespace tirpol::twin {

using namespace acquisition;

TwinWorld::TwinWorld(simulation::SensorModel sensor, Band band, int width, int height)
    : m_sensor(std::move(sensor)), m_band(std::move(band)), m_width(width), m_height(height) {
    if (!m_sensor.counts) fail("twin: the sensor model needs a counts model to play the camera");
}

TwinWorld::TwinWorld(simulation::DofpSensor dofp, ReferencePolarizer reference, Band band)
    : m_dofp(std::move(dofp)),
      m_reference(reference),
      m_band(std::move(band)),
      m_width(m_dofp->width()),
      m_height(m_dofp->height()) {
    if (!(m_reference.transmission > 0.0 && m_reference.transmission <= 1.0) ||
        !(m_reference.extinction_ratio >= 1.0) || !(m_reference.emitted_radiance >= 0.0))
        fail(
            "twin: reference polarizer with transmission {}, extinction ratio {}, emission {} "
            "(expected (0, 1], ≥ 1, ≥ 0)",
            m_reference.transmission, m_reference.extinction_ratio, m_reference.emitted_radiance);
}

void TwinWorld::set_flat_field_backdrop(std::optional<double> temperature_k) {
    std::lock_guard lock(m_mutex);
    m_backdrop_k = temperature_k;
}

std::optional<std::array<double, 4>> TwinWorld::microgrid_pattern_deg() const {
    if (!m_dofp) return std::nullopt;
    return m_dofp->spec().pattern_deg;
}

std::vector<float> TwinWorld::dofp_frame(const Exposure& e, std::uint64_t realisation) {
    if (e.blackbody_k)
        return m_dofp->frame(blackbody_image(*e.blackbody_k), realisation).channel("counts");
    if (!e.backdrop_k) {
        if (m_scene.pixel_count() == 0) fail("twin: no scene set before the camera was read");
        return m_dofp->frame(m_scene, realisation).channel("counts");
    }
    // The blackbody behind the reference polarizer at the stage's angle φ: a diattenuator on
    // unpolarized light gives ½L·(τ + τ_min, (τ − τ_min) cos 2φ, (τ − τ_min) sin 2φ) (Chipman, Lam
    // & Young 2018 eq 6.35), plus the polarizer's own unpolarized emission.
    const double l = m_band.radiance(*e.backdrop_k);
    const double tau = m_reference.transmission, tau_min = tau / m_reference.extinction_ratio;
    const double two_phi = 2.0 * e.angle_deg * kPi / 180.0;
    Image source(m_width, m_height);
    source.add_channel(
        "S0", static_cast<float>(0.5 * l * (tau + tau_min) + m_reference.emitted_radiance));
    source.add_channel("S1", static_cast<float>(0.5 * l * (tau - tau_min) * std::cos(two_phi)));
    source.add_channel("S2", static_cast<float>(0.5 * l * (tau - tau_min) * std::sin(two_phi)));
    source.add_channel("S3", 0.0f);
    return m_dofp->frame(source, realisation).channel("counts");
}

void TwinWorld::set_scene(Image stokes) {
    if (stokes.width() != m_width || stokes.height() != m_height)
        fail("twin: scene image is {}×{}, the camera {}×{}", stokes.width(), stokes.height(),
             m_width, m_height);
    std::lock_guard lock(m_mutex);
    m_scene = std::move(stokes);
}

void TwinWorld::set_polarizer_in_beam(bool in_beam) {
    std::lock_guard lock(m_mutex);
    m_polarizer_in_beam = in_beam;
}

void TwinWorld::place_blackbody(double temperature_k) {
    std::lock_guard lock(m_mutex);
    m_pending_blackbody_k = temperature_k;
}

void TwinWorld::on_stage_move() {
    std::lock_guard lock(m_mutex);
    m_blackbody_k = m_pending_blackbody_k;
    m_pending_blackbody_k.reset();
}

void TwinWorld::on_stage_arrived() {
    std::lock_guard lock(m_mutex);
    ++m_stay;
    m_sent_in_stay = 0;
    m_kept_in_stay = 0;
}

namespace {
/// The sensor model mixes a realisation into 32 bits (sensor_model.cpp), and the DoFP sensor stores
/// it as an int attribute: stays beyond 2¹⁸ would overflow both.
constexpr std::uint64_t kRealisationBase = std::uint64_t{1} << 30;
constexpr std::uint64_t kPlacesPerStay = std::uint64_t{1} << 12;
constexpr std::uint64_t kSentFrom = kPlacesPerStay / 2;
constexpr std::uint64_t kMaxStays = std::uint64_t{1} << 18;
/// Exposures remembered for take(): a camera nobody takes frames from (sim://) must not grow them.
constexpr std::size_t kMaxExposures = 1024;
}  // namespace

std::uint64_t TwinWorld::realisation(std::uint64_t place) const {
    if (m_stay >= kMaxStays)
        fail("twin: {} stage moves in one run, more than the {} the noise realisations number",
             m_stay, kMaxStays);
    return kRealisationBase + m_stay * kPlacesPerStay + place;
}

std::vector<float> TwinWorld::render(const Exposure& e, std::uint64_t realisation) {
    if (m_dofp) return dofp_frame(e, realisation);
    const Image& source = e.blackbody_k ? blackbody_image(*e.blackbody_k) : m_scene;
    if (source.pixel_count() == 0) fail("twin: no scene set before the camera was read");
    return sensor_frame(source, e.angle_deg, e.polarizer_in_beam, realisation);
}

void TwinWorld::set_angle_deg(double angle_deg) {
    std::lock_guard lock(m_mutex);
    m_angle_deg = angle_deg;
}

double TwinWorld::angle_deg() const {
    std::lock_guard lock(m_mutex);
    return m_angle_deg;
}

const Image& TwinWorld::blackbody_image(double temperature_k) {
    const long key = std::lround(temperature_k * 1000.0);
    auto it = m_blackbodies.find(key);
    if (it != m_blackbodies.end()) return it->second;
    Image bb(m_width, m_height);
    bb.add_channel("S0", static_cast<float>(m_band.radiance(temperature_k)));
    for (const char* c : {"S1", "S2", "S3"}) bb.add_channel(c, 0.0f);
    return m_blackbodies.emplace(key, std::move(bb)).first->second;
}

void TwinWorld::fill(double angle_deg, std::vector<float>& counts) {
    fill(angle_deg, counts, host_realtime_ns());
}

void TwinWorld::fill(double angle_deg, std::vector<float>& counts, std::int64_t exposure_end_ns) {
    std::lock_guard lock(m_mutex);
    Exposure e{exposure_end_ns, angle_deg, m_blackbody_k, m_backdrop_k, m_polarizer_in_beam, 0.0};
    counts = render(e, realisation(kSentFrom + m_sent_in_stay++ % kSentFrom));
    double sum = 0.0;
    for (float c : counts) sum += c;
    e.sent_mean = counts.empty() ? 0.0 : sum / static_cast<double>(counts.size());
    if (m_exposures.size() == kMaxExposures) m_exposures.pop_front();
    m_exposures.push_back(e);
}

void TwinWorld::take(std::int64_t exposure_end_ns, std::vector<float>& counts) {
    std::lock_guard lock(m_mutex);
    // Frames arrive in the order they were filled; those passed over were lost on the way.
    while (!m_exposures.empty() && m_exposures.front().end_ns < exposure_end_ns)
        m_exposures.pop_front();
    if (m_exposures.empty())
        fail("twin: the capture took a frame exposed until {} ns that the camera did not fill",
             exposure_end_ns);
    const Exposure e = m_exposures.front();
    m_exposures.pop_front();
    double sum = 0.0;
    for (float c : counts) sum += c;
    const double mean = counts.empty() ? 0.0 : sum / static_cast<double>(counts.size());
    if (!(std::abs(mean - e.sent_mean) <= 0.5))
        fail(
            "twin: the frame exposed until {} ns arrived with mean counts {:.3f}, the camera sent "
            "{:.3f} (more than the ADC's rounding apart)",
            exposure_end_ns, mean, e.sent_mean);
    if (m_kept_in_stay >= kSentFrom)
        fail("twin: more than {} frames kept in one stay of the stage", kSentFrom);
    counts = render(e, realisation(m_kept_in_stay));
}

void TwinWorld::frame_kept() {
    std::lock_guard lock(m_mutex);
    ++m_kept_in_stay;
}

std::vector<float> TwinWorld::sensor_frame(const Image& stokes, double angle_deg,
                                           bool polarizer_in_beam,
                                           std::uint64_t frame_index) const {
    simulation::SensorModel model = m_sensor;
    model.analyzer.angles_deg = {angle_deg};
    if (!polarizer_in_beam) {
        // Polarizer out of the beam: no diattenuation, no grid reflection or emission.
        model.analyzer.transmission = 1.0;
        model.analyzer.extinction_ratio = 1.0;
        model.background = {};
    }
    return simulation::polarizer_images(stokes, model, m_band, frame_index)
        .front()
        .channel("counts");
}

simulation::SensorModel twin_sensor(const Band& band, double air_temperature_k) {
    simulation::SensorModel s;
    s.analyzer.transmission = 0.7;
    s.analyzer.extinction_ratio = 400.0;
    s.background.reflectance = 0.05;
    s.background.reflected_radiance =
        band.radiance(240.0);  // clear night sky, brightness temperature ~240 K
    s.background.emissivity = 0.03;
    s.background.temperature_k = air_temperature_k;
    s.counts = simulation::CountsModel{800.0, 3000.0, 0.05, 300.0};
    s.seed = 9;
    return s;
}

Status WorldReportingStage::home(std::chrono::milliseconds timeout) {
    m_world.on_stage_move();
    Status done = m_inner.home(timeout);
    m_world.on_stage_arrived();
    return done;
}

Status WorldReportingStage::move_absolute(double angle_deg, std::chrono::milliseconds timeout) {
    m_world.on_stage_move();
    Status done = m_inner.move_absolute(angle_deg, timeout);
    m_world.on_stage_arrived();
    return done;
}

Result<double> WorldReportingStage::position_deg() {
    Result<double> r = m_inner.position_deg();
    if (r.ok()) m_world.set_angle_deg(r.value());
    return r;
}

namespace {

/// The camera as the capture loop sees it: each frame it hands out is taken from the world
/// (TwinWorld::take), which redraws its noise by the frames the loop's gate kept, and rounded to
/// the camera's whole counts. `stamped_on_host_clock`: the device stamps the end of the exposure
/// on the host's clock (the fake GigE camera); otherwise the frame's host stamp, taken just before
/// the world fills it (the in-process camera), finds it.
class WorldTakingCamera final : public Camera {
public:
    WorldTakingCamera(Camera& inner, TwinWorld& world, bool stamped_on_host_clock)
        : m_inner(inner),
          m_world(world),
          m_device_stamps(stamped_on_host_clock),
          m_full_scale(std::ldexp(1.0, inner.info().bits_per_pixel) - 1.0) {}
    CameraInfo info() const override { return m_inner.info(); }
    Status set_pixel_format(const std::string& format) override {
        return m_inner.set_pixel_format(format);
    }
    Status set_frame_rate(double hz) override { return m_inner.set_frame_rate(hz); }
    Status start() override { return m_inner.start(); }
    Status stop() override { return m_inner.stop(); }
    Result<Frame> grab(std::chrono::milliseconds timeout) override {
        Result<Frame> frame = m_inner.grab(timeout);
        if (!frame.ok()) return frame;
        Frame& f = frame.value();
        m_world.take(m_device_stamps ? f.device_timestamp_ns : f.host_timestamp_ns, f.counts);
        for (float& c : f.counts)
            c = static_cast<float>(
                std::clamp(std::nearbyint(static_cast<double>(c)), 0.0, m_full_scale));
        return frame;
    }
    StreamStatistics statistics() const override { return m_inner.statistics(); }
    std::optional<double> device_temperature_k() override { return m_inner.device_temperature_k(); }

private:
    Camera& m_inner;
    TwinWorld& m_world;
    bool m_device_stamps;
    double m_full_scale;
};

}  // namespace

/// What TwinInstrument owns, in construction order: the stage simulator serving its pty, the real
/// serial driver on the other end, the world-reporting stage, and the camera (over loopback GigE
/// Vision, or in-process). Destroyed in reverse: the camera stops before the world it reads.
struct TwinInstrument::Devices {
    Devices(TwinWorld& world, StageProtocol protocol, bool gige, std::filesystem::path xml);
    ~Devices();
    Devices(const Devices&) = delete;
    Devices& operator=(const Devices&) = delete;

    void open_stage_driver(const std::string& uri);
    void open_camera_over_gige();
    void open_in_process_camera(const std::string& why_not);

    TwinWorld& world;
    StageProtocol protocol;
    std::filesystem::path genicam_xml;
    StageSimulator simulator;
    PseudoTerminal pty;
    std::atomic<bool> stop{false};
    std::thread stage_thread;
    std::unique_ptr<Stage> driver;
    std::unique_ptr<WorldReportingStage> stage;
    int gige_lock_fd = -1;
    std::unique_ptr<FakeGigECameraServer> server;
    std::unique_ptr<Camera> camera;
    std::string camera_transport;
};

namespace {

StageSimulatorOptions simulator_options(StageProtocol protocol) {
    StageSimulatorOptions o;
    o.protocol = protocol == StageProtocol::Apt ? SimProtocol::Apt : SimProtocol::Elliptec;
    // Faster than a K10CR1 (≈ 10°/s) so the demo does not wait on the mount; ELL14-like for
    // Elliptec.
    o.deg_per_s = 720.0;
    return o;
}

}  // namespace

TwinInstrument::Devices::Devices(TwinWorld& w, StageProtocol p, bool gige,
                                 std::filesystem::path xml)
    : world(w),
      protocol(p),
      genicam_xml(std::move(xml)),
      simulator(simulator_options(p)),
      pty(PseudoTerminal::open().value_or_throw()) {
    stage_thread = std::thread([this] { serve_stage_simulator(simulator, pty, stop); });
    open_stage_driver(protocol == StageProtocol::Apt
                          ? "thorlabs-apt://" + pty.slave_path()
                          : "elliptec://" + pty.slave_path() + "?address=0");
    if (gige) {
        try {
            open_camera_over_gige();
        } catch (const std::exception& e) {
            camera.reset();
            server.reset();
            open_in_process_camera(e.what());
        }
    } else {
        open_in_process_camera("GigE Vision not requested");
    }
}

void TwinInstrument::Devices::open_stage_driver(const std::string& uri) {
    try {
        driver = open_stage(uri).value_or_throw();
    } catch (...) {
        stop = true;
        stage_thread.join();
        throw;
    }
    stage = std::make_unique<WorldReportingStage>(*driver, world);
}

void TwinInstrument::Devices::open_camera_over_gige() {
    // One loopback GigE Vision camera at a time on this machine (tests use the same lock).
    gige_lock_fd = ::open("/tmp/tirpol-loopback-gige.lock", O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (gige_lock_fd >= 0) ::flock(gige_lock_fd, LOCK_EX);
    // A microgrid camera streams its raw mosaic in a polarized format (LUCID's PolarizeMono16),
    // which Aravis's built-in XML does not offer.
    const auto pattern = world.microgrid_pattern_deg();
    if (pattern && genicam_xml.empty())
        fail("no GenICam XML offering PolarizeMono16 was given for the microgrid camera");
    FakeGigECameraOptions server_options;
    server_options.genicam_xml = genicam_xml;
    server = std::make_unique<FakeGigECameraServer>(server_options);
    // Free-running, as a field camera: each frame shows the polarizer where the simulated mount
    // physically is when the frame is exposed, also mid-move; the capture loop's gate must
    // discard those (no software trigger needed).
    server->set_fill([this](const FakeGigEFrameRequest& request, std::vector<float>& counts) {
        // Time-true: the mount where it was when the exposure ended (the frame's stamp), not when
        // this thread got round to filling it.
        const auto since_stamp =
            std::chrono::nanoseconds(host_realtime_ns() - request.timestamp_ns);
        const auto exposure_end = StageSimulator::Clock::now() -
                                  std::chrono::duration_cast<StageSimulator::Clock::duration>(
                                      std::max(since_stamp, std::chrono::nanoseconds(0)));
        world.fill(simulator.physical_angle_deg(exposure_end), counts, request.timestamp_ns);
    });
    // A microgrid bolometer free-runs at 60 Hz; the rotating-polarizer camera at Aravis's default.
    const std::string camera_uri =
        pattern ? fmt::format("aravis://{}?pixel_format=PolarizeMono16&width={}&height={}&fps=60",
                              server->device_id(), world.width(), world.height())
                : fmt::format("aravis://{}?pixel_format=Mono16&width={}&height={}",
                              server->device_id(), world.width(), world.height());
    auto opened = open_camera(camera_uri);
    if (!opened.ok()) fail("{}", opened.error().message);
    camera = std::move(opened).value_or_throw();
    camera_transport = fmt::format("GigE Vision on {} ({})", server->interface(), camera_uri);
}

void TwinInstrument::Devices::open_in_process_camera(const std::string& why_not) {
    SimulatedCameraConfig config;
    config.name = "twin";
    config.width = world.width();
    config.height = world.height();
    config.bits_per_pixel = 16;
    config.microgrid_pattern_deg = world.microgrid_pattern_deg();
    if (config.microgrid_pattern_deg) config.frame_rate_hz = 60.0;
    camera = std::make_unique<SimulatedCamera>(
        config, [this](double angle, std::vector<float>& counts) { world.fill(angle, counts); },
        [this] { return simulator.physical_angle_deg(StageSimulator::Clock::now()); });
    camera_transport = "in-process SimulatedCamera (FALLBACK: " + why_not + ")";
}

TwinInstrument::Devices::~Devices() {
    camera.reset();
    server.reset();
    if (gige_lock_fd >= 0) ::close(gige_lock_fd);
    stage.reset();
    driver.reset();
    stop = true;
    if (stage_thread.joinable()) stage_thread.join();
}

TwinInstrument::TwinInstrument(TwinWorld& world, StageProtocol protocol, bool gige,
                               std::filesystem::path genicam_xml)
    : m_devices(std::make_unique<Devices>(world, protocol, gige, std::move(genicam_xml))) {}

TwinInstrument::~TwinInstrument() = default;

const std::string& TwinInstrument::camera_transport() const { return m_devices->camera_transport; }

bool TwinInstrument::served_over_gige() const { return m_devices->server != nullptr; }

std::string TwinInstrument::stage_description() const {
    const StageInfo i = m_devices->driver->info();
    return fmt::format("{} {} (serial {}) over the {} protocol on {} ({})", i.vendor, i.model,
                       i.serial,
                       m_devices->protocol == StageProtocol::Apt ? "Thorlabs APT" : "Elliptec",
                       m_devices->pty.slave_path(), i.uri);
}

CaptureSummary TwinInstrument::acquire(const CapturePlan& plan, const std::filesystem::path& dir) {
    Devices& d = *m_devices;
    // The simulated operator: the capture loop asks before each reference step, in plan order.
    std::deque<double> temperatures;
    for (const CaptureStep& s : plan_steps(plan))
        if (s.kind == RecordKind::Blackbody) temperatures.push_back(*s.temperature_k);
    d.world.set_polarizer_in_beam(plan.metadata.value("polarizer_in_beam", false));
    std::filesystem::remove_all(dir);
    SessionWriter session =
        SessionWriter::create(dir, new_session_manifest(d.camera->info(), d.stage->info(), plan));
    CaptureOptions options;
    options.progress_stream = nullptr;
    options.prompt = [&](const std::string& instruction) {
        if (temperatures.empty())
            fail("twin: the capture loop asked for an unplanned reference: {}", instruction);
        d.world.place_blackbody(temperatures.front());
        temperatures.pop_front();
        return true;
    };
    // The gate's verdict numbers the noise realisations of the frames the capture keeps.
    options.on_progress = [&](const CaptureProgress& p) {
        if (p.event == CaptureProgress::Event::Frame) d.world.frame_kept();
    };
    WorldTakingCamera camera(*d.camera, d.world, d.server != nullptr);
    return run_capture(camera, *d.stage, plan, session, options);
}

}  // namespace tirpol::twin
