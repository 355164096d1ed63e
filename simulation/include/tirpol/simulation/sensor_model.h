#pragma once
/// \file sensor_model.h
/// A digital twin of the field camera behind a rotating wire-grid polarizer (paper §3.1): from a
/// rendered Stokes image (camera frame), the images I(α) the camera would record through a
/// non-ideal analyzer, optionally in counts through a gain/offset with temporal noise set by an
/// NEDT.
///
/// The physics is core's forward instrument model (instrument_model.h), which calibration's
/// synthetic sessions share: per polarizer angle α (band radiance, W/(m²·sr))
///   I(α) = [P(α + offset) · S]₀ + ρ_grid·L_reflected + ε_grid·L_bb(T_grid)
/// where P is a linear diattenuator with major transmittance τ and extinction ratio τ/τ_min
/// (core polarizer_with_extinction; Chipman, Lam & Young 2018 eq 6.35), and the last two terms are
/// what the tilted grid adds (the paper's reflected cold-sky background and the grid's own
/// emission). Counts: C = gain·I + offset + N(0, σ), σ = gain·NEDT·dL/dT(T_ref) — the noise of a
/// camera whose noise-equivalent temperature difference at T_ref is NEDT. Deterministic given the
/// seed.

#include <cstdint>
#include <optional>
#include <vector>

#include "tirpol/core/config.h"
#include "tirpol/core/image.h"
#include "tirpol/core/instrument_model.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::simulation {

struct SimulatedAnalyzer {
    std::vector<double> angles_deg{0.0, 45.0, 90.0, 135.0};
    double transmission = 0.7;        ///< major-axis intensity transmittance τ
    double extinction_ratio = 400.0;  ///< τ/τ_min (the paper's wire grid, §3.1)
    double angle_offset_deg = 0.0;    ///< mount misalignment added to every angle
};

struct WireGridBackground {
    double reflectance = 0.0;         ///< ρ_grid seen by the camera
    double reflected_radiance = 0.0;  ///< band radiance reflected into the camera, W/(m²·sr)
    double emissivity = 0.0;          ///< ε_grid
    double temperature_k = 293.15;    ///< grid temperature
};

struct CountsModel {
    double gain_counts_per_radiance = 1000.0;  ///< counts per W/(m²·sr)
    double offset_counts = 0.0;
    double nedt_k = 0.08;  ///< temporal noise as a temperature difference (0: noiseless)
    double reference_temperature_k = 300.0;  ///< where the NEDT is specified
};

struct SensorModel {
    SimulatedAnalyzer analyzer;
    WireGridBackground background;
    std::optional<CountsModel> counts;
    std::uint64_t seed = 1;

    /// From a YAML mapping with optional `analyzer`, `background`, `counts`, `seed`
    /// (docs/simulation.md).
    static SensorModel from_config(const ConfigNode& node);
    /// The analyzer and grid background as core's forward model (grid emission over `band`).
    WireGridPolarizer wire_grid(const Band& band) const;
};

/// One image per analyzer angle, in the order of `model.analyzer.angles_deg`: channel `radiance`
/// (W/(m²·sr)) and, with a counts model, `counts`; attributes polarizer_angle_deg, frame_index.
/// `stokes` needs channels S0 S1 S2 S3 in the camera frame. `frame_index` selects an independent
/// noise realisation (temporal noise of consecutive frames).
std::vector<Image> polarizer_images(const Image& stokes, const SensorModel& model, const Band& band,
                                    std::uint64_t frame_index = 0);

}  // namespace tirpol::simulation
