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
///
/// A synthetic microgrid (division-of-focal-plane) bolometer camera with known truth, for tests,
/// docs figures and the Python module: every pixel has its own micro-polarizer (transmission t_i,
/// diattenuation d_i, axis θ_i spread about the pattern's angles, Powell & Gruev 2013) in front of
/// a bolometer with its own responsivity R_i and offset o_i (the non-uniformity a two-point NUC
/// removes), temporal noise, and planted bad pixels:
///
///   counts_i = R_i·½·t_i·(S0 + d_i·(S1 cos 2θ_i + S2 sin 2θ_i)) + o_i + noise,
///
/// S in band radiance W/(m² sr). Sessions are written with core's SessionWriter (schema v5, the
/// pattern recorded), so they are what `tirpol acquire` writes with a microgrid camera, a blackbody
/// and a reference polarizer on the stage.

#include <Eigen/Core>
#include <array>
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

struct SyntheticMicrogridCamera {
    int width = 64, height = 48;
    std::array<double, 4> pattern_deg{90.0, 45.0, 135.0, 0.0};  ///< Sony IMX250MZR layout
    /// Manufacturing spread of the micro-polarizers (fraction): t_i uniform in 1 ± spread, d_i
    /// uniform in [0.98 − spread, 0.98], θ_i normal about the nominal angle with σ = 10°·spread.
    double analyzer_spread = 0.1;
    double gain_mean = 100.0, gain_rel_std = 0.05;  ///< R_i, counts per W/(m² sr)
    double offset_mean = 5000.0, offset_std = 150.0;
    double noise_counts = 6.0;  ///< temporal σ of one frame
    int frames = 16;            ///< frames averaged per record
    int bits_per_pixel = 14;
    /// Planted bad pixels (x, y): dead (R = 2 % of the mean), hot (+4000 counts offset), noisy
    /// (8 × the temporal noise).
    int dead_x = 5, dead_y = 5, hot_x = 9, hot_y = 30, noisy_x = 40, noisy_y = 12;
    unsigned seed = 1;
    /// Draws the temporal noise of the sessions written (not the pixels): another capture_seed is
    /// a repeated capture with the same camera.
    unsigned capture_seed = 0;
    /// The flat-field rig: the open blackbody at these temperatures (the two-point NUC) and the
    /// reference polarizer (transmission, its own unpolarized emission and reflection in W/(m² sr),
    /// axis offset of the stage's zero) at these angles in front of the blackbody at these.
    std::vector<double> open_blackbody_k{288.15, 318.15};
    std::vector<double> polarizer_blackbody_k{293.15, 323.15};
    std::vector<double> reference_angles_deg{0.0, 22.5, 45.0, 67.5, 90.0, 112.5, 135.0, 157.5};
    double reference_transmission = 0.85;
    double reference_emission_radiance = 1.5;
    double reference_axis_offset_deg = 0.0;
};

/// The planted truth of every pixel (row-major planes).
struct SyntheticMicrogridTruth {
    std::vector<double> transmission, diattenuation, axis_deg, responsivity, offset, noise_counts;
};

/// The camera's pixels, drawn from `camera.seed` (the same camera every call).
SyntheticMicrogridTruth synthetic_microgrid_truth(const SyntheticMicrogridCamera& camera);

/// One record's frame (channels `counts`, `counts_std`: the mean of camera.frames frames and
/// their per-pixel σ) of a scene given as band-radiance Stokes planes (channels S0 S1 S2, camera
/// size). Throws tirpol::Error for a scene of another size or without those channels.
Image synthetic_microgrid_frame(const SyntheticMicrogridCamera& camera,
                                const SyntheticMicrogridTruth& truth, const Image& scene,
                                unsigned seed);

/// A uniform scene of Stokes `stokes` (S0 S1 S2) at the camera's size.
Image uniform_stokes_scene(const SyntheticMicrogridCamera& camera, const Eigen::Vector3d& stokes);

/// Writes the flat-field session of microgrid_flat_field.h's conventions to `dir`: open
/// blackbody records at camera.open_blackbody_k, then the reference polarizer at every angle in
/// front of the blackbody at each of camera.polarizer_blackbody_k (one repeat per temperature).
void write_synthetic_microgrid_flat_field(const std::filesystem::path& dir,
                                          const SyntheticMicrogridCamera& camera, const Band& band);

/// Writes a session of one polarizer record (the stage unused) of `scene` (S0 S1 S2) to `dir`.
void write_synthetic_microgrid_scene(const std::filesystem::path& dir,
                                     const SyntheticMicrogridCamera& camera, const Image& scene);

}  // namespace tirpol::calibration
