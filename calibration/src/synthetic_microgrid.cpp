#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "tirpol/calibration/synthetic_session.h"
#include "tirpol/core/error.h"
#include "tirpol/core/session.h"

namespace tirpol::calibration {

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

SessionManifest base_manifest(const SyntheticMicrogridCamera& camera) {
    SessionManifest m;
    m.created_utc = utc_now_iso8601();
    m.camera = {"sim://synthetic-microgrid",
                "tirpol",
                "synthetic-microgrid-bolometer",
                "MG01",
                "Mono16",
                camera.width,
                camera.height,
                camera.bits_per_pixel,
                30.0,
                {},
                camera.pattern_deg};
    m.stage = {"sim://stage", "tirpol", "synthetic-stage", "0001", "1.0", 1000.0};
    return m;
}

struct RecordClock {
    std::int64_t t_ns = 1795359560000000000;
    SessionRecord next(RecordKind kind, const std::string& stem, double angle_deg, int repeat,
                       std::optional<double> blackbody_k, int frames) {
        SessionRecord r;
        r.kind = kind;
        r.file = session_frame_file(stem);
        r.angle_deg_requested = angle_deg;
        r.angle_deg_measured = angle_deg;
        r.repeat = repeat;
        r.blackbody_temperature_k = blackbody_k;
        r.frames = frames;
        r.first_timestamp_ns = t_ns;
        t_ns += 500000000;
        r.last_timestamp_ns = t_ns;
        return r;
    }
};

}  // namespace

SyntheticMicrogridTruth synthetic_microgrid_truth(const SyntheticMicrogridCamera& camera) {
    if (camera.width < 4 || camera.height < 4 || camera.width % 2 || camera.height % 2)
        fail("synthetic microgrid camera: {}×{}; expected even width and height ≥ 4", camera.width,
             camera.height);
    if (!(camera.analyzer_spread >= 0.0 && camera.analyzer_spread < 0.5))
        fail("synthetic microgrid camera: analyzer_spread {} is outside [0, 0.5)",
             camera.analyzer_spread);
    std::mt19937 rng(camera.seed);
    const double spread = camera.analyzer_spread;
    std::uniform_real_distribution<double> t(1.0 - spread, 1.0 + spread), d(0.98 - spread, 0.98);
    std::normal_distribution<double> axis(0.0, 10.0 * spread), unit(0.0, 1.0);
    SyntheticMicrogridTruth truth;
    for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width; ++x) {
            const double nominal =
                camera.pattern_deg[static_cast<std::size_t>((y % 2) * 2 + x % 2)];
            truth.transmission.push_back(t(rng));
            truth.diattenuation.push_back(d(rng));
            truth.axis_deg.push_back(nominal + axis(rng));
            truth.responsivity.push_back(camera.gain_mean *
                                         (1.0 + camera.gain_rel_std * unit(rng)));
            truth.offset.push_back(camera.offset_mean + camera.offset_std * unit(rng));
            truth.noise_counts.push_back(camera.noise_counts);
        }
    auto at = [&](int x, int y) {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(camera.width) +
               static_cast<std::size_t>(x);
    };
    truth.responsivity[at(camera.dead_x, camera.dead_y)] = 0.02 * camera.gain_mean;
    truth.offset[at(camera.hot_x, camera.hot_y)] += 4000.0;
    truth.noise_counts[at(camera.noisy_x, camera.noisy_y)] *= 8.0;
    return truth;
}

Image synthetic_microgrid_frame(const SyntheticMicrogridCamera& camera,
                                const SyntheticMicrogridTruth& truth, const Image& scene,
                                unsigned seed) {
    if (scene.width() != camera.width || scene.height() != camera.height)
        fail("synthetic microgrid frame: scene is {}×{}; expected the camera's {}×{}",
             scene.width(), scene.height(), camera.width, camera.height);
    const auto& s0 = scene.channel("S0");
    const auto& s1 = scene.channel("S1");
    const auto& s2 = scene.channel("S2");
    std::mt19937 rng(seed);
    std::normal_distribution<double> unit(0.0, 1.0);
    Image frame(camera.width, camera.height);
    auto& counts = frame.add_channel("counts");
    auto& counts_std = frame.add_channel("counts_std");
    const double saturation = std::ldexp(1.0, camera.bits_per_pixel) - 1.0;
    const double frames = static_cast<double>(camera.frames);
    std::chi_squared_distribution<double> sample_variance(std::max(frames - 1.0, 1.0));
    for (std::size_t i = 0; i < counts.size(); ++i) {
        const double two_theta = 2.0 * kDegToRad * truth.axis_deg[i];
        const double signal = truth.responsivity[i] * 0.5 * truth.transmission[i] *
                                  (s0[i] + truth.diattenuation[i] * (s1[i] * std::cos(two_theta) +
                                                                     s2[i] * std::sin(two_theta))) +
                              truth.offset[i];
        const double sigma = truth.noise_counts[i];
        counts[i] = static_cast<float>(
            std::min(saturation, signal + sigma / std::sqrt(frames) * unit(rng)));
        // The sample σ of N normal frames: s² = σ²·χ²(N−1)/(N−1), so E[s²] = σ² exactly (what
        // a test of stated against observed variance needs); 0 for one frame, as a session says.
        counts_std[i] =
            camera.frames > 1
                ? static_cast<float>(sigma * std::sqrt(sample_variance(rng) / (frames - 1.0)))
                : 0.0f;
    }
    return frame;
}

Image uniform_stokes_scene(const SyntheticMicrogridCamera& camera, const Eigen::Vector3d& stokes) {
    Image scene(camera.width, camera.height);
    scene.add_channel("S0", static_cast<float>(stokes(0)));
    scene.add_channel("S1", static_cast<float>(stokes(1)));
    scene.add_channel("S2", static_cast<float>(stokes(2)));
    return scene;
}

void write_synthetic_microgrid_flat_field(const std::filesystem::path& dir,
                                          const SyntheticMicrogridCamera& camera,
                                          const Band& band) {
    const SyntheticMicrogridTruth truth = synthetic_microgrid_truth(camera);
    SessionManifest m = base_manifest(camera);
    nlohmann::json repeats = nlohmann::json::array();
    for (std::size_t k = 0; k < camera.polarizer_blackbody_k.size(); ++k)
        repeats.push_back({{"repeat", static_cast<int>(k)},
                           {"blackbody_temperature_k", camera.polarizer_blackbody_k[k]}});
    m.metadata = {{"site", "laboratory"},
                  {"polarizer_in_beam", false},
                  {"microgrid_flat_field",
                   {{"reference_polarizer_axis_offset_deg", camera.reference_axis_offset_deg},
                    {"polarizer_repeats", repeats}}}};
    auto writer = SessionWriter::create(dir, m);
    RecordClock clock;
    unsigned seed = camera.seed * 1000u + camera.capture_seed * 104729u;
    for (double t_k : camera.open_blackbody_k)
        writer.add_record(
            clock.next(RecordKind::Blackbody, fmt::format("bb_{:.2f}K", t_k), 0.0, 0, t_k,
                       camera.frames),
            synthetic_microgrid_frame(camera, truth,
                                      uniform_stokes_scene(camera, {band.radiance(t_k), 0.0, 0.0}),
                                      ++seed));
    for (std::size_t k = 0; k < camera.polarizer_blackbody_k.size(); ++k) {
        const double radiance = band.radiance(camera.polarizer_blackbody_k[k]);
        for (double angle : camera.reference_angles_deg) {
            // An ideal reference polarizer of transmission t at φ adds its own unpolarized
            // emission and reflection: S = ½·t·L·(1, cos 2φ, sin 2φ) + (E, 0, 0).
            const double two_phi = 2.0 * kDegToRad * (angle + camera.reference_axis_offset_deg);
            const double half = 0.5 * camera.reference_transmission * radiance;
            const Eigen::Vector3d s(half + camera.reference_emission_radiance,
                                    half * std::cos(two_phi), half * std::sin(two_phi));
            writer.add_record(
                clock.next(RecordKind::Polarizer, fmt::format("pol_{:.1f}deg_r{}", angle, k), angle,
                           static_cast<int>(k), std::nullopt, camera.frames),
                synthetic_microgrid_frame(camera, truth, uniform_stokes_scene(camera, s), ++seed));
        }
    }
    writer.mark_complete();
}

void write_synthetic_microgrid_scene(const std::filesystem::path& dir,
                                     const SyntheticMicrogridCamera& camera, const Image& scene) {
    const SyntheticMicrogridTruth truth = synthetic_microgrid_truth(camera);
    SessionManifest m = base_manifest(camera);
    m.metadata = {{"site", "laboratory"}};
    auto writer = SessionWriter::create(dir, m);
    RecordClock clock;
    writer.add_record(
        clock.next(RecordKind::Polarizer, "scene_r0", 0.0, 0, std::nullopt, camera.frames),
        synthetic_microgrid_frame(camera, truth, scene,
                                  camera.seed * 7919u + 1u + camera.capture_seed * 15485863u));
    writer.mark_complete();
}

}  // namespace tirpol::calibration
