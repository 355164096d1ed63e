#include "tirpol/acquisition/sim/simulated_camera.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <ctime>

#include "pixel_formats.h"
#include "tirpol/acquisition/device_uri.h"
#include "tirpol/core/error.h"

namespace tirpol::acquisition {

namespace {
constexpr std::int64_t kTimestampOriginNs = 1'000'000'000;  ///< virtual device clock starts at 1 s

std::int64_t realtime_now_ns() {
    timespec ts{};
    clock_gettime(CLOCK_REALTIME, &ts);
    return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

std::optional<int> mono_bits(const std::string& format) {
    for (int bits : {8, 10, 12, 14, 16})
        if (format == fmt::format("Mono{}", bits)) return bits;
    return std::nullopt;
}

/// The significant bits of a microgrid camera's polarized format (pixel_formats.h), if it is one.
std::optional<int> polarized_bits(const std::string& format) {
    const GenICamPixelFormat* f = find_pixel_format(format);
    if (f == nullptr || !f->polarized) return std::nullopt;
    return f->significant_bits;
}

/// The name a camera of this depth reports before any set_pixel_format.
std::string default_pixel_format(const SimulatedCameraConfig& config) {
    const std::string polarized = fmt::format("PolarizeMono{}", config.bits_per_pixel);
    if (config.microgrid_pattern_deg && find_pixel_format(polarized) != nullptr) return polarized;
    return fmt::format("Mono{}", config.bits_per_pixel);
}
}  // namespace

SimulatedCamera::SimulatedCamera(SimulatedCameraConfig config, FrameGenerator generator,
                                 AngleSource angle)
    : m_config(std::move(config)),
      m_generator(std::move(generator)),
      m_angle(std::move(angle)),
      m_pixel_format(default_pixel_format(m_config)),
      m_rng(m_config.seed) {
    if (m_config.width <= 0 || m_config.height <= 0)
        fail("simulated camera '{}': size {}×{} (expected positive)", m_config.name, m_config.width,
             m_config.height);
    if (m_config.bits_per_pixel < 1 || m_config.bits_per_pixel > 16)
        fail("simulated camera '{}': bits_per_pixel {} (expected 1…16)", m_config.name,
             m_config.bits_per_pixel);
    if (!(m_config.frame_rate_hz > 0.0))
        fail("simulated camera '{}': frame rate {} Hz (expected > 0)", m_config.name,
             m_config.frame_rate_hz);
    if (!(m_config.noise_std_counts >= 0.0))
        fail("simulated camera '{}': noise {} counts (expected ≥ 0)", m_config.name,
             m_config.noise_std_counts);
    if (!(m_config.drop_probability >= 0.0 && m_config.drop_probability < 1.0))
        fail("simulated camera '{}': drop probability {} (expected in [0, 1))", m_config.name,
             m_config.drop_probability);
    if (m_config.buffers < 1)
        fail("simulated camera '{}': {} buffers (expected ≥ 1)", m_config.name, m_config.buffers);
    if (!m_generator) fail("simulated camera '{}': no frame generator", m_config.name);
}

SimulatedCamera::~SimulatedCamera() { (void)stop(); }

StreamStatistics SimulatedCamera::statistics() const {
    std::lock_guard lock(m_mutex);
    return m_stats;
}

CameraInfo SimulatedCamera::info() const {
    CameraInfo info;
    info.uri = "sim://" + m_config.name;
    info.vendor = "tirpol";
    info.model = "simulated (" + m_config.name + ")";
    info.serial = fmt::format("seed-{}", m_config.seed);
    info.pixel_format = m_pixel_format;
    info.microgrid_pattern_deg = m_config.microgrid_pattern_deg;
    info.width = m_config.width;
    info.height = m_config.height;
    info.bits_per_pixel = m_config.bits_per_pixel;
    info.frame_rate_hz = m_config.frame_rate_hz;
    return info;
}

Status SimulatedCamera::set_pixel_format(const std::string& format) {
    auto bits = mono_bits(format);
    if (!bits && m_config.microgrid_pattern_deg) bits = polarized_bits(format);
    if (!bits)
        return DeviceError{
            DeviceErrorCode::InvalidArgument,
            fmt::format("sim://{}: pixel format '{}' (expected Mono8, Mono10, Mono12, Mono14 or "
                        "Mono16{})",
                        m_config.name, format,
                        m_config.microgrid_pattern_deg
                            ? ", or PolarizeMono8, PolarizeMono12, PolarizeMono12p, PolarizeMono16"
                            : "")};
    m_config.bits_per_pixel = *bits;
    m_pixel_format = format;
    return ok_status();
}

Status SimulatedCamera::set_frame_rate(double hz) {
    if (!(hz > 0.0) || !std::isfinite(hz))
        return DeviceError{DeviceErrorCode::InvalidArgument,
                           fmt::format("sim://{}: frame rate {} Hz", m_config.name, hz)};
    std::lock_guard lock(m_mutex);
    if (m_streaming)
        return DeviceError{DeviceErrorCode::InvalidArgument,
                           "sim://" + m_config.name + ": frame rate change while streaming"};
    m_config.frame_rate_hz = hz;
    return ok_status();
}

Status SimulatedCamera::start() {
    std::lock_guard lock(m_mutex);
    if (m_streaming) return ok_status();
    m_streaming = true;
    m_started = std::chrono::steady_clock::now();
    m_thread = std::thread([this] { expose_frames(); });
    return ok_status();
}

Status SimulatedCamera::stop() {
    {
        std::lock_guard lock(m_mutex);
        m_streaming = false;
        m_queue.clear();
    }
    m_changed.notify_all();
    if (m_thread.joinable()) m_thread.join();
    return ok_status();
}

Result<Frame> SimulatedCamera::grab(std::chrono::milliseconds timeout) {
    std::unique_lock lock(m_mutex);
    if (!m_streaming)
        return DeviceError{DeviceErrorCode::InvalidArgument,
                           "sim://" + m_config.name + ": grab() before start()"};
    if (!m_changed.wait_for(lock, timeout, [this] { return !m_queue.empty() || !m_streaming; }) ||
        m_queue.empty())
        return DeviceError{DeviceErrorCode::Timeout, fmt::format("sim://{}: no frame within {} ms",
                                                                 m_config.name, timeout.count())};
    Frame frame = std::move(m_queue.front());
    m_queue.pop_front();
    ++m_stats.delivered;
    return frame;
}

void SimulatedCamera::expose_frames() {
    using Clock = std::chrono::steady_clock;
    const auto period = std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(1.0 / m_config.frame_rate_hz));
    auto due = Clock::now() + period;
    std::unique_lock lock(m_mutex);
    while (m_streaming) {
        if (m_changed.wait_until(lock, due, [this] { return !m_streaming; })) break;
        const std::uint64_t id = m_next_id++;
        std::bernoulli_distribution drop(m_config.drop_probability);
        if (m_config.drop_probability > 0.0 && drop(m_rng)) {
            ++m_stats.dropped;  // lost in the camera: an id gap
        } else if (m_queue.size() >= static_cast<std::size_t>(m_config.buffers)) {
            ++m_stats.dropped;  // no free buffer on the host: the frame is lost
        } else {
            lock.unlock();  // render without blocking grab()
            auto frame = expose_one(id);
            lock.lock();
            if (frame && m_streaming) {
                m_queue.push_back(std::move(*frame));
                m_changed.notify_all();
            } else if (!frame) {
                ++m_stats.incomplete;
            }
        }
        due += period;
        // A camera slower than its nominal rate (a heavy generator) runs late rather than bursting.
        if (const auto now = Clock::now(); now > due) due = now;
    }
}

void SimulatedCamera::set_angle_source(AngleSource angle) {
    std::lock_guard lock(m_mutex);
    m_angle = std::move(angle);
}

bool SimulatedCamera::has_angle_source() const {
    std::lock_guard lock(m_mutex);
    return static_cast<bool>(m_angle);
}

std::optional<Frame> SimulatedCamera::expose_one(std::uint64_t id) {
    const std::size_t n =
        static_cast<std::size_t>(m_config.width) * static_cast<std::size_t>(m_config.height);
    m_expected.assign(n, 0.0f);
    FrameGenerator generator;
    AngleSource angle;
    {
        std::lock_guard lock(m_mutex);
        generator = m_generator;
        angle = m_angle;
    }
    // The angle is read at the end of the exposure, and the frame is stamped at that same instant:
    // stamped after the generator ran, a frame whose thread was held up (a slow generator, a
    // loaded machine) would show the polarizer as it was before its stamp by more than the capture
    // loop's exposure window, and a frame exposed mid-move could pass for one exposed after the
    // settle.
    const double angle_deg = angle ? angle() : 0.0;
    const std::int64_t device_timestamp_ns =
        kTimestampOriginNs + std::chrono::duration_cast<std::chrono::nanoseconds>(
                                 std::chrono::steady_clock::now() - m_started)
                                 .count();
    const std::int64_t host_timestamp_ns = realtime_now_ns();
    generator(angle_deg, m_expected);
    if (m_expected.size() != n) {
        spdlog::error("sim://{}: the frame generator returned {} values for {}×{} pixels",
                      m_config.name, m_expected.size(), m_config.width, m_config.height);
        return std::nullopt;
    }
    Frame frame;
    frame.width = m_config.width;
    frame.height = m_config.height;
    frame.counts.resize(n);
    const double full_scale = std::ldexp(1.0, m_config.bits_per_pixel) - 1.0;
    std::normal_distribution<double> noise(0.0, 1.0);
    const bool noisy = m_config.noise_std_counts > 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        double v = m_expected[i];
        if (noisy) v += m_config.noise_std_counts * noise(m_rng);
        frame.counts[i] = static_cast<float>(std::clamp(std::nearbyint(v), 0.0, full_scale));
    }
    frame.frame_id = id;
    frame.device_timestamp_ns = device_timestamp_ns;
    frame.host_timestamp_ns = host_timestamp_ns;
    frame.fpa_temperature_k = m_config.fpa_temperature_k;
    return frame;
}

std::unique_ptr<SimulatedCamera> open_simulated_camera(const std::string& uri) {
    const DeviceUri u = parse_device_uri(uri);
    if (u.scheme != "sim") fail("device URI '{}': expected the sim:// scheme", uri);
    if (u.target != "uniform")
        fail(
            "device URI '{}': unknown simulated camera '{}' (built in: uniform; scene files "
            "sim://<scene.yaml> once the digital twin registered its renderer-backed camera)",
            uri, u.target);
    u.check_keys({"width", "height", "counts", "noise", "fps", "bits", "drop", "seed", "fpa_k",
                  "buffers", "microgrid"});
    SimulatedCameraConfig config;
    config.name = "uniform";
    config.width = u.integer("width", 640);
    config.height = u.integer("height", 512);
    config.bits_per_pixel = u.integer("bits", 16);
    config.frame_rate_hz = u.number("fps", 30.0);
    config.noise_std_counts = u.number("noise", 0.0);
    config.drop_probability = u.number("drop", 0.0);
    config.seed = static_cast<std::uint64_t>(u.integer("seed", 1));
    config.buffers = u.integer("buffers", config.buffers);
    if (u.query.count("fpa_k") != 0) config.fpa_temperature_k = u.number("fpa_k", 0.0);
    if (const auto it = u.query.find("microgrid"); it != u.query.end())
        config.microgrid_pattern_deg =
            parse_microgrid_pattern_deg(it->second, fmt::format("device URI '{}': microgrid", uri));
    const double counts = u.number("counts", 8000.0);
    auto generator = [counts](double, std::vector<float>& out) {
        std::fill(out.begin(), out.end(), static_cast<float>(counts));
    };
    return std::make_unique<SimulatedCamera>(config, generator);
}

}  // namespace tirpol::acquisition
