#pragma once
/// \file simulated_camera.h
/// `sim://` cameras: a Camera fed by a frame generator, for tests and the digital twin (apps/ plugs the
/// renderer's sensor model in as the generator; acquisition never depends on simulation/).
/// Each grab: expected counts = generator(current polarizer angle), plus Gaussian temporal noise,
/// rounded and clipped to the pixel format's range like a real ADC; frame ids count up from 1 with
/// optional injected drops; device timestamps follow a virtual clock at the configured frame rate.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "tirpol/acquisition/camera.h"

namespace tirpol::acquisition {

struct SimulatedCameraConfig {
    std::string name = "sim";    ///< shown in the URI and model name
    int width = 640, height = 512;
    int bits_per_pixel = 16;     ///< ADC depth: counts are clipped to [0, 2^bits − 1]
    double frame_rate_hz = 30.0; ///< spacing of the device timestamps (no real-time pacing)
    double noise_std_counts = 0.0;    ///< temporal noise, standard deviation in counts
    double drop_probability = 0.0;    ///< chance that a frame is lost (its id is skipped)
    std::uint64_t seed = 1;           ///< noise and drops are reproducible for a given seed
    std::optional<double> fpa_temperature_k;
};

/// Writes the noise-free expected counts (width × height, row-major) for a polarizer at `angle_deg`.
using FrameGenerator = std::function<void(double angle_deg, std::vector<float>& counts)>;
/// The current polarizer angle in degrees (e.g. read from a simulated stage).
using AngleSource = std::function<double()>;

class SimulatedCamera final : public Camera {
public:
    /// `angle` may be empty: the generator then always sees 0°. Throws tirpol::Error for a bad config.
    SimulatedCamera(SimulatedCameraConfig config, FrameGenerator generator, AngleSource angle = {});

    CameraInfo info() const override;
    /// Accepts Mono8 … Mono16 (sets the ADC depth).
    Status set_pixel_format(const std::string& format) override;
    Status set_frame_rate(double hz) override;
    Status start() override;
    Status stop() override;
    Result<Frame> grab(std::chrono::milliseconds timeout) override;
    StreamStatistics statistics() const override { return m_stats; }
    std::optional<double> device_temperature_k() override { return m_config.fpa_temperature_k; }

    /// Replaces the generator (e.g. a new scene); takes effect at the next grab.
    void set_generator(FrameGenerator generator) { m_generator = std::move(generator); }

private:
    SimulatedCameraConfig m_config;
    FrameGenerator m_generator;
    AngleSource m_angle;
    bool m_streaming = false;
    std::uint64_t m_next_id = 1;
    StreamStatistics m_stats;
    std::mt19937_64 m_rng;
    std::vector<float> m_expected;
};

/// `sim://uniform?width=W&height=H&counts=C&noise=N&fps=F[&bits=B&drop=P&seed=S&fpa_k=T]`: every pixel
/// has expected value C (default 640×512, C = 8000, N = 0, F = 30, B = 16). Throws tirpol::Error naming
/// the query key for an unknown key or a bad value.
std::unique_ptr<SimulatedCamera> open_simulated_camera(const std::string& uri);

}  // namespace tirpol::acquisition
