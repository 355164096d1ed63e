#pragma once
/// \file synthetic_session.h
/// Synthetic capture sessions with known truth, for tests, the demo and the benchmark: an uncooled
/// camera (per-pixel gain/offset, planted bad pixels, temporal noise, an offset drift between
/// laboratory and field), a non-ideal wire grid (extinction ratio, mount angle offset, vignetting),
/// the grid's ghost of the camera interior, its reflection of the cold sky and its own emission.
/// The polarizer, grid and detector are core's forward instrument model (instrument_model.h), the
/// one simulation's sensor model and the digital twin use. Written with core's SessionWriter, so
/// they are what `tirpol acquire` would write. Used by the demo, the Python module's
/// write_synthetic_sessions and the tests.

#include <filesystem>
#include <vector>

#include "tirpol/core/image.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::calibration {

struct SyntheticCamera {
    int width = 64, height = 48;
    double gain_mean = 100.0, gain_rel_std = 0.05;  ///< counts per W/(m²·sr)
    double offset_mean = 5000.0, offset_std = 150.0;
    double noise_counts = 6.0;  ///< temporal σ of one frame
    int frames = 16;            ///< frames averaged per record
    int bits_per_pixel = 14;
    double field_offset_drift = 60.0;  ///< counts added between the laboratory and the field
    /// Planted bad pixels (x, y): a dead one, a hot one, a noisy one.
    int dead_x = 5, dead_y = 5, hot_x = 9, hot_y = 30, noisy_x = 40, noisy_y = 12;
    double extinction_ratio = 100.0, angle_offset_deg = 1.5, t_max = 0.8;
    double vignetting = 0.3;  ///< the polarizer's transmission falls as 1 − vignetting·r² (r:
                              ///< offset from centre / size)
    double sky_temperature_k = 230.0, grid_reflectance = 0.15, grid_emissivity = 0.04,
           grid_temperature_k = 285.0;
    double sky_polarization = 0.3;  ///< the reflected sky varies as 1 + sky_polarization·cos 2α
    double ghost_radiance = 1.5;    ///< peak of the ghost blob, W/(m²·sr)
    unsigned seed = 1;
    std::vector<double> angles_deg{0.0, 45.0, 90.0, 135.0};
};

/// The counts a record would hold for a scene Stokes image (channels S0 S1 S2, band radiance over
/// `band`) seen through the polarizer at `angle_deg` (or without it when `through_polarizer` is
/// false); the grid's sky reflection and emission are integrated over `band` too.
Image synthetic_record_frame(const SyntheticCamera& cam, const Image& scene, const Band& band,
                             double angle_deg, bool through_polarizer, bool field, unsigned seed);

/// Writes three sessions under `root`: `lab/` (blackbody at 283–328 K, no polarizer), `polcal/`
/// (blackbody at 278 and 308 K through the polarizer at every angle, and a blackbody at 2
/// temperatures behind a reference polarizer at 0/45/90/135° as the known source), and `scene/`
/// (the `scene` Stokes image at every angle, plus a shutter frame at 293.15 K).
void write_synthetic_sessions(const std::filesystem::path& root, const SyntheticCamera& cam,
                              const Image& scene, const Band& band);

/// A test scene: background at 280 K, an IR reflector (S0 = L of a 230 K sky) at the left, a panel
/// at 300 K with ε_S0 = 0.93, ε_S1 = −0.035, ε_S2 = 0.01 in the middle; returns S0 S1 S2.
Image synthetic_panel_scene(int width, int height, const Band& band);

}  // namespace tirpol::calibration
