// The twin's instrument: world state, the sensor model as the camera's detector, and the devices.

#include "tirpol/twin/instrument.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <unistd.h>

#include <cmath>
#include <deque>

#include "tirpol/acquisition/camera_registry.h"
#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/simulated_camera.h"
#include "tirpol/acquisition/stage_registry.h"
#include "tirpol/core/error.h"
#include "tirpol/core/log.h"
#include "tirpol/core/session.h"

namespace tirpol::twin {

using namespace acquisition;

TwinWorld::TwinWorld(simulation::SensorModel sensor, Band band, int width, int height)
    : m_sensor(std::move(sensor)), m_band(std::move(band)), m_width(width), m_height(height) {
    if (!m_sensor.counts) fail("twin: the sensor model needs a counts model to play the camera");
}

void TwinWorld::set_scene(Image stokes) {
    if (stokes.width() != m_width || stokes.height() != m_height)
        fail("twin: scene image is {}×{}, the camera {}×{}", stokes.width(), stokes.height(), m_width, m_height);
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
    std::lock_guard lock(m_mutex);
    const Image& source = m_blackbody_k ? blackbody_image(*m_blackbody_k) : m_scene;
    if (source.pixel_count() == 0) fail("twin: no scene set before the camera was read");
    counts = sensor_frame(source, angle_deg, m_polarizer_in_beam, ++m_frame_index);
}

std::vector<float> TwinWorld::sensor_frame(const Image& stokes, double angle_deg, bool polarizer_in_beam,
                                           std::uint64_t frame_index) const {
    simulation::SensorModel model = m_sensor;
    model.analyzer.angles_deg = {angle_deg};
    if (!polarizer_in_beam) {
        // Polarizer out of the beam: no diattenuation, no grid reflection or emission.
        model.analyzer.transmission = 1.0;
        model.analyzer.extinction_ratio = 1.0;
        model.background = {};
    }
    return simulation::polarizer_images(stokes, model, m_band, frame_index).front().channel("counts");
}

simulation::SensorModel twin_sensor(const Band& band, double air_temperature_k) {
    simulation::SensorModel s;
    s.analyzer.transmission = 0.7;
    s.analyzer.extinction_ratio = 400.0;
    s.background.reflectance = 0.05;
    s.background.reflected_radiance = band.radiance(240.0);  // clear night sky, brightness temperature ~240 K
    s.background.emissivity = 0.03;
    s.background.temperature_k = air_temperature_k;
    s.counts = simulation::CountsModel{800.0, 3000.0, 0.05, 300.0};
    s.seed = 9;
    return s;
}

Status WorldReportingStage::home(std::chrono::milliseconds timeout) {
    m_world.on_stage_move();
    return m_inner.home(timeout);
}

Status WorldReportingStage::move_absolute(double angle_deg, std::chrono::milliseconds timeout) {
    m_world.on_stage_move();
    return m_inner.move_absolute(angle_deg, timeout);
}

Result<double> WorldReportingStage::position_deg() {
    Result<double> r = m_inner.position_deg();
    if (r.ok()) m_world.set_angle_deg(r.value());
    return r;
}

namespace {

StageSimulatorOptions simulator_options(SimProtocol protocol) {
    StageSimulatorOptions o;
    o.protocol = protocol;
    // Faster than a K10CR1 (≈ 10°/s) so the demo does not wait on the mount; ELL14-like for Elliptec.
    o.deg_per_s = 720.0;
    return o;
}

}  // namespace

TwinInstrument::TwinInstrument(TwinWorld& world, SimProtocol protocol, bool gige)
    : m_world(world), m_protocol(protocol), m_simulator(simulator_options(protocol)) {
    m_pty.emplace(PseudoTerminal::open().value_or_throw());
    m_stage_thread = std::thread([this] { serve_stage_simulator(m_simulator, *m_pty, m_stop); });
    const std::string uri = protocol == SimProtocol::Apt ? "thorlabs-apt://" + m_pty->slave_path()
                                                         : "elliptec://" + m_pty->slave_path() + "?address=0";
    try {
        m_driver = open_stage(uri).value_or_throw();
    } catch (...) {
        m_stop = true;
        m_stage_thread.join();
        throw;
    }
    m_stage = std::make_unique<WorldReportingStage>(*m_driver, m_world);

    const int w = world.width(), h = world.height();
    std::string why_not;
    if (gige) {
        try {
            // One loopback GigE Vision camera at a time on this machine (tests use the same lock).
            m_gige_lock_fd = ::open("/tmp/tirpol-loopback-gige.lock", O_RDWR | O_CREAT | O_CLOEXEC, 0666);
            if (m_gige_lock_fd >= 0) ::flock(m_gige_lock_fd, LOCK_EX);
            m_server = std::make_unique<FakeGigECameraServer>();
            // Free-running, as a field camera: each frame shows the polarizer where the simulated mount
            // physically is when the frame is exposed, also mid-move; the capture loop's gate must
            // discard those (no software trigger needed).
            m_server->set_fill([this](const FakeGigEFrameRequest&, std::vector<float>& counts) {
                m_world.fill(m_simulator.physical_angle_deg(StageSimulator::Clock::now()), counts);
            });
            const std::string camera_uri =
                fmt::format("aravis://{}?pixel_format=Mono16&width={}&height={}", m_server->device_id(), w, h);
            auto opened = open_camera(camera_uri);
            if (!opened.ok()) fail("{}", opened.error().message);
            m_camera = std::move(opened).value_or_throw();
            m_camera_transport = fmt::format("GigE Vision on {} ({})", m_server->interface(), camera_uri);
        } catch (const std::exception& e) {
            why_not = e.what();
            m_camera.reset();
            m_server.reset();
        }
    } else {
        why_not = "GigE Vision not requested";
    }
    if (!m_camera) {
        SimulatedCameraConfig config;
        config.name = "twin";
        config.width = w;
        config.height = h;
        config.bits_per_pixel = 16;
        m_camera = std::make_unique<SimulatedCamera>(
            config, [this](double angle, std::vector<float>& counts) { m_world.fill(angle, counts); },
            [this] { return m_simulator.physical_angle_deg(StageSimulator::Clock::now()); });
        m_camera_transport = "in-process SimulatedCamera (FALLBACK: " + why_not + ")";
    }
}

TwinInstrument::~TwinInstrument() {
    m_camera.reset();
    m_server.reset();
    if (m_gige_lock_fd >= 0) ::close(m_gige_lock_fd);
    m_stage.reset();
    m_driver.reset();
    m_stop = true;
    if (m_stage_thread.joinable()) m_stage_thread.join();
}

std::string TwinInstrument::stage_description() const {
    const StageInfo i = m_driver->info();
    return fmt::format("{} {} (serial {}) over the {} protocol on {} ({})", i.vendor, i.model, i.serial,
                       m_protocol == SimProtocol::Apt ? "Thorlabs APT" : "Elliptec", m_pty->slave_path(), i.uri);
}

void TwinInstrument::acquire(const CapturePlan& plan, const std::filesystem::path& dir) {
    // The simulated operator: the capture loop asks before each reference step, in plan order.
    std::deque<double> temperatures;
    for (const CaptureStep& s : plan_steps(plan))
        if (s.kind == RecordKind::Blackbody) temperatures.push_back(*s.temperature_k);
    m_world.set_polarizer_in_beam(plan.metadata.value("polarizer_in_beam", false));
    std::filesystem::remove_all(dir);
    SessionWriter session = SessionWriter::create(dir, new_session_manifest(m_camera->info(), m_stage->info(), plan));
    CaptureOptions options;
    options.progress_stream = nullptr;
    options.prompt = [&](const std::string& instruction) {
        if (temperatures.empty()) fail("twin: the capture loop asked for an unplanned reference: {}", instruction);
        m_world.place_blackbody(temperatures.front());
        temperatures.pop_front();
        return true;
    };
    run_capture(*m_camera, *m_stage, plan, session, options);
}

}  // namespace tirpol::twin
