#include "synthetic_fpa_camera.h"

#include <fmt/format.h>

#include <cmath>
#include <random>

namespace tirpol::calibration {

DriftingCameraTruth::DriftingCameraTruth(const DriftingCamera& cam) : m_cam(cam) {
    std::mt19937 rng(cam.seed);
    std::normal_distribution<double> unit(0.0, 1.0);
    const std::size_t n =
        static_cast<std::size_t>(cam.width) * static_cast<std::size_t>(cam.height);
    for (std::size_t i = 0; i < n; ++i) {
        m_g0.push_back(cam.gain_mean * (1.0 + cam.gain_rel_std * unit(rng)));
        m_o0.push_back(cam.offset_mean + cam.offset_std * unit(rng));
        m_o1.push_back(cam.offset_per_k + cam.offset_per_k_std * unit(rng));
        m_gamma.push_back(cam.gain_rel_per_k + cam.gain_rel_per_k_std * unit(rng));
    }
}

double DriftingCameraTruth::counts(std::size_t i, double radiance, double fpa_k) const {
    const double dt = fpa_k - m_cam.reference_fpa_k;
    return m_o0[i] + m_o1[i] * dt + m_g0[i] * (1.0 + m_gamma[i] * dt) * radiance;
}

BlackbodyFrame DriftingCameraTruth::frame(const Band& band, double scene_k, double fpa_k,
                                          unsigned seed) const {
    std::mt19937 rng(seed);
    std::normal_distribution<double> unit(0.0, 1.0);
    const double l = band.radiance(scene_k);
    const double sigma_mean = m_cam.noise_counts / std::sqrt(static_cast<double>(m_cam.frames));
    BlackbodyFrame f;
    f.temperature_k = scene_k;
    f.fpa_temperature_k = fpa_k;
    f.frames = m_cam.frames;
    f.source = fmt::format("synthetic blackbody {:.2f} K at FPA {:.2f} K", scene_k, fpa_k);
    f.counts.resize(m_o0.size());
    f.counts_std.assign(m_o0.size(), static_cast<float>(m_cam.noise_counts));
    for (std::size_t i = 0; i < m_o0.size(); ++i)
        f.counts[i] = static_cast<float>(counts(i, l, fpa_k) + sigma_mean * unit(rng));
    return f;
}

}  // namespace tirpol::calibration
