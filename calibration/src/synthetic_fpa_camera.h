#pragma once
/// \file synthetic_fpa_camera.h
/// A synthetic uncooled camera whose per-pixel gain and offset follow its own focal-plane-array
/// temperature, for tests and benchmarks of the FPA-dependent calibration (docs/calibration.md):
/// counts = o₀ + o₁·ΔT + g₀·(1 + γ·ΔT)·L + noise, ΔT = T_fpa − reference_fpa_k, with o₁ and γ
/// varying from pixel to pixel.

#include <vector>

#include "tirpol/calibration/radiometric.h"

namespace tirpol::calibration {

struct DriftingCamera {
    int width = 32, height = 24;
    double gain_mean = 100.0, gain_rel_std = 0.05;                ///< g₀, counts per W/(m²·sr)
    double offset_mean = 5000.0, offset_std = 150.0;              ///< o₀, counts
    double reference_fpa_k = 303.15;                              ///< where o₀, g₀ hold
    double offset_per_k = 60.0, offset_per_k_std = 6.0;           ///< o₁, counts/K
    double gain_rel_per_k = -0.006, gain_rel_per_k_std = 0.0005;  ///< γ, 1/K
    double noise_counts = 4.0;                                    ///< temporal σ of one frame
    int frames = 16;  ///< frames averaged per BlackbodyFrame
    unsigned seed = 7;
};

/// The camera's per-pixel truth, drawn once from cam.seed.
class DriftingCameraTruth {
public:
    explicit DriftingCameraTruth(const DriftingCamera& cam);
    /// Noise-free counts of pixel i for in-band radiance `radiance` (W/(m²·sr)) at FPA temperature
    /// `fpa_k`.
    double counts(std::size_t i, double radiance, double fpa_k) const;
    /// The averaged frame of a uniform blackbody at `scene_k` seen at `fpa_k`, with temporal noise
    /// (mean of cam.frames frames; counts_std = the per-frame σ), tagged with both temperatures.
    BlackbodyFrame frame(const Band& band, double scene_k, double fpa_k, unsigned seed) const;

private:
    DriftingCamera m_cam;
    std::vector<double> m_o0, m_o1, m_g0, m_gamma;
};

}  // namespace tirpol::calibration
