#pragma once
/// \file renderer.h
/// The polarized path tracer (paper §2.2–2.3.3). For each pixel and sample, a camera ray is traced
/// into the scene; at every hit the surface's polarized emission ε(θ)·L_bb(λ, T) (eq 13) and its
/// reflection of what arrives from an importance-sampled direction (eq 12) are accumulated, with
/// the Stokes vector carried in world ray frames and rotated with core's change_frame between the
/// surface s/p frames of the pBRDF and the world frames; the sun is added by next-event estimation
/// with a shadow ray; escaped rays take the sky. Each path carries one wavelength node of the
/// band's spectral grid (spectral_grid), drawn with probability ∝ its quadrature weight; emission
/// is read from the emissivity table's column at exactly that node and reflection is evaluated at
/// it, so ε + ρ = 1 holds per path and an isothermal enclosure is a blackbody for any n,k(λ).
/// Reflection is estimated with a control variate, (e0 − ε)·L_ref exactly plus the sampled
/// reflection of L_in − L_ref (RenderOptions::control_variate; docs/simulation.md).
///
/// Why path tracing rather than the paper's hemisphere sampling with a bounce-dependent decay:
/// one sample per bounce spends the ray budget on pixels (anti-aliasing, edge pixels, sub-pixel
/// geometry) instead of on deep branches that contribute little; the noise-vs-time comparison is in
/// bench/simulation_bench.cpp and docs/simulation.md.

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/core/image.h"
#include "tirpol/simulation/scene.h"

namespace tirpol::simulation {

/// Receives every ray query a render makes, in the order each thread makes them (benchmarks replay
/// them through bare Embree to price the shading; bench/simulation_bench.cpp). Called concurrently
/// from the render threads: implementations synchronise.
class RayRecorder {
public:
    virtual ~RayRecorder() = default;
    /// A nearest-hit query (`occlusion` false) or a shadow query along origin + t·direction, t <
    /// t_max.
    virtual void record(const Vec3& origin, const Vec3& direction, double t_max,
                        bool occlusion) = 0;
};

struct RenderOptions {
    int threads = 0;             ///< 0: all cores (TBB's default concurrency)
    bool show_progress = false;  ///< progress bar with ETA on stderr (core ProgressReporter)
    int tile_size = 16;          ///< pixels per tile edge; the image does not depend on it
    /// Folder of the on-disk emissivity-table cache (materials emissivity_cache.h); unset: the
    /// default
    /// ($TIRPOL_CACHE_DIR, $XDG_CACHE_HOME/tirpol or ~/.cache/tirpol); empty: memory cache only.
    std::optional<std::filesystem::path> emissivity_cache_dir;
    RayRecorder* ray_recorder = nullptr;  ///< not owned; null: no recording (no cost)
    /// Not owned; checked before each tile: once true, the remaining tiles are skipped and render()
    /// throws tirpol::Cancelled (how the Python module stops a render on Ctrl-C). Null: never.
    const std::atomic<bool>* cancel = nullptr;
    /// Estimate each vertex's reflected radiance as (e0 − ε)·L_ref + (sampled ∫M·(L_in −
    /// L_ref)·cosθi dωi), a control variate whose first term is exact by Kirchhoff's law (the
    /// emissivity table's own ε); L_ref is the sky along the mirror direction, or the vertex's
    /// blackbody radiance when that points below the horizon. Unbiased either way; on: ~5× lower S1
    /// noise on panels_night at 16 spp, and an isothermal enclosure renders L_bb exactly. Off: the
    /// plain estimator, for tests of the sampling. Unset: the scene's sampling.estimator (default
    /// on).
    std::optional<bool> control_variate;
    /// Not owned; null: every pixel. Otherwise width·height entries (row-major): only pixels with a
    /// nonzero entry are traced, the others hold NaN in every channel. A traced pixel's values do
    /// not depend on the mask (its random numbers are its own), so a fit can render only its
    /// regions.
    const std::vector<std::uint8_t>* pixel_mask = nullptr;
};

struct RenderStatistics {
    double seconds = 0.0;        ///< wall time of the whole render
    double setup_seconds = 0.0;  ///< of which building the materials' emissivity tables
    double trace_cpu_seconds =
        0.0;  ///< CPU time of the render threads in the pixel loop, summed over threads
    std::uint64_t camera_rays = 0;
    std::uint64_t scene_rays = 0;     ///< every intersect query (camera, bounce and auxiliary rays)
    std::uint64_t shadow_rays = 0;    ///< occlusion queries toward the sun
    int emissivity_tables_built = 0;  ///< computed in this render (no valid cache entry)
    int emissivity_tables_from_disk = 0;    ///< read from the disk cache
    int emissivity_tables_from_memory = 0;  ///< already held by this process
};

/// Width of the Gauss–Legendre panels (8 nodes each, split at the RSR's knots) of the spectral
/// grid.
inline constexpr double kSpectralGridPanel_um = 1.0;

/// The wavelength nodes and weights the renderer samples for `band`: the same band (and RSR)
/// integrated on panels of kSpectralGridPanel_um, i.e. 8 nodes per µm. Its quadrature of Planck's
/// law agrees with band.radiance to < 1e-9 relative; each node gets its own emissivity-table
/// column.
Band spectral_grid(const Band& band);

/// Renders `scene` at its camera's resolution with its sampling settings. Returns an image with the
/// channels S0 S1 S2 S3 (camera frame: 0° along image +x, 90° toward the image top; band radiance
/// W/(m²·sr)), DoLP, AoP (degrees, [0, 180)), S0_var S1_var S2_var S3_var (unbiased variance of the
/// per-pixel mean from the spread of replicate_count() independently scrambled replicates, with
/// replicates − 1 degrees of freedom, attribute `variance_dof`; NaN with one sample per pixel),
/// depth (m along the pixel-centre ray), normal_x/y/z (world, facing the camera), view_zenith_deg,
/// object_id, material_id (−1 on sky), temperature_k; NaN on sky pixels for the geometric channels.
/// Header attributes: units, band, spp (rendered_samples_per_pixel), replicates, variance_dof,
/// seed, bounces, scene file. The result is identical for any thread count and tile size (every
/// random number is a function of seed, pixel, replicate, sample and dimension: sobol_sampler.h),
/// and memory does not grow with spp. Throws tirpol::Error before rendering if a material does not
/// cover the band, tirpol::Cancelled if `options.cancel` was set.
Image render(const Scene& scene, const RenderOptions& options = {},
             RenderStatistics* statistics = nullptr);

}  // namespace tirpol::simulation
