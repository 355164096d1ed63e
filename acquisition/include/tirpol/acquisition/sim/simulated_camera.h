#pragma once
/// \file simulated_camera.h
/// `sim://` cameras: a Camera fed by a frame generator, for tests and the digital twin (apps/ plugs
/// the renderer's sensor model in as the generator; acquisition never depends on simulation/).
/// Free-running like a real sensor: from start() a thread of the camera's own exposes a frame every
/// 1/frame_rate_hz of wall time, whether or not anyone grabs, and queues it in a ring of `buffers`
/// frames; a frame that finds the ring full is lost (counted as dropped, as an Aravis stream counts
/// an underrun). So frames keep coming while the stage moves, and grab() returns the oldest queued
/// one, which may predate the move — exactly what the capture loop must cope with. Each frame:
/// expected counts = generator(polarizer angle at the end of its exposure), plus Gaussian temporal
/// noise, rounded and clipped to the pixel format's range like a real ADC; frame ids count up from
/// 1 with optional injected drops; the host timestamp is the instant the frame left the sensor
/// (CLOCK_REALTIME), the device timestamp the camera's own clock (steady, from 1 s at start()). A
/// camera too slow for its rate (a heavy generator) runs slower instead of bursting.

#include <array>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "tirpol/acquisition/camera.h"

namespace tirpol::acquisition {

struct SimulatedCameraConfig {
    std::string name = "sim";  ///< shown in the URI and model name
    int width = 640, height = 512;
    int bits_per_pixel = 16;      ///< ADC depth: counts are clipped to [0, 2^bits − 1]
    double frame_rate_hz = 30.0;  ///< frames per second of wall time (and device-timestamp spacing)
    int buffers = 16;             ///< host-side queue; a frame that finds it full is dropped
    double noise_std_counts = 0.0;  ///< temporal noise, standard deviation in counts
    double drop_probability = 0.0;  ///< chance that a frame is lost (its id is skipped)
    std::uint64_t seed = 1;         ///< noise and drops are reproducible for a given seed
    std::optional<double> fpa_temperature_k;
    /// A microgrid (division-of-focal-plane) camera: its analyzer angles at cell positions (0,0),
    /// (0,1), (1,0), (1,1) (camera.h), reported in CameraInfo; it streams its raw mosaic in
    /// `PolarizeMono<bits>` (or `PolarizeMono12p`, set_pixel_format). Unset: a plain camera.
    std::optional<std::array<double, 4>> microgrid_pattern_deg;
};

/// Writes the noise-free expected counts (width × height, row-major) for a polarizer at
/// `angle_deg`. Called on the camera's thread: must be safe to call concurrently with the rest of
/// the program.
using FrameGenerator = std::function<void(double angle_deg, std::vector<float>& counts)>;
/// The physical polarizer angle now, in degrees (e.g. a simulated stage's time-true position).
/// Called on the camera's thread.
using AngleSource = std::function<double()>;

class SimulatedCamera final : public Camera {
public:
    /// `angle` may be empty: the generator then always sees 0°. Throws tirpol::Error for a bad
    /// config.
    SimulatedCamera(SimulatedCameraConfig config, FrameGenerator generator, AngleSource angle = {});
    ~SimulatedCamera() override;
    SimulatedCamera(const SimulatedCamera&) = delete;
    SimulatedCamera& operator=(const SimulatedCamera&) = delete;

    CameraInfo info() const override;
    /// Accepts Mono8 … Mono16 and, for a microgrid camera, the polarized formats PolarizeMono8,
    /// PolarizeMono12, PolarizeMono12p and PolarizeMono16 (sets the ADC depth).
    Status set_pixel_format(const std::string& format) override;
    Status set_frame_rate(double hz) override;
    Status start() override;
    Status stop() override;
    Result<Frame> grab(std::chrono::milliseconds timeout) override;
    StreamStatistics statistics() const override;
    std::optional<double> device_temperature_k() override { return m_config.fpa_temperature_k; }
    /// Replaces the polarizer-angle source (empty: 0°). Safe while streaming: the next frame uses
    /// it.
    void set_angle_source(AngleSource angle);
    bool has_angle_source() const;

private:
    void expose_frames();  ///< the camera's thread
    std::optional<Frame> expose_one(std::uint64_t id);

    SimulatedCameraConfig m_config;
    std::string m_pixel_format;  ///< what info() reports; set_pixel_format runs before start()
    FrameGenerator m_generator;  ///< guarded by m_mutex
    AngleSource m_angle;         ///< guarded by m_mutex
    mutable std::mutex m_mutex;
    std::condition_variable m_changed;
    bool m_streaming = false;                         ///< guarded by m_mutex
    std::deque<Frame> m_queue;                        ///< guarded by m_mutex
    StreamStatistics m_stats;                         ///< guarded by m_mutex
    std::uint64_t m_next_id = 1;                      ///< camera thread only
    std::chrono::steady_clock::time_point m_started;  ///< set by start() before the thread runs
    std::mt19937_64 m_rng;                            ///< camera thread only
    std::vector<float> m_expected;                    ///< camera thread only
    std::thread m_thread;
};

/// `sim://uniform?width=W&height=H&counts=C&noise=N&fps=F[&bits=B&drop=P&seed=S&fpa_k=T&buffers=Q&microgrid=M]`:
/// every pixel has expected value C (default 640×512, C = 8000, N = 0, F = 30, B = 16, Q = 16);
/// `microgrid=sony` or four angles makes it a microgrid camera with that pattern.
/// Throws tirpol::Error naming the query key for an unknown key or a bad value.
std::unique_ptr<SimulatedCamera> open_simulated_camera(const std::string& uri);

}  // namespace tirpol::acquisition
