#pragma once
/// \file emissivity.h
/// Kirchhoff-consistent polarized directional emissivity (paper eq 5 generalized to Stokes):
///   ε(θo) = e0 − ∫_{2π} M(wi→wo)·e0 cosθi dωi,   e0 = (1, 0, 0, 0),
/// i.e. the emitted Stokes vector is what an isothermal black enclosure (uniform unpolarized
/// illumination) would not see reflected. Stokes in surface_frame(wo, z) (pbrdf.h): S1 < 0 is
/// emission polarized in the plane of emission. For an isotropic surface S2 = S3 = 0 by mirror
/// symmetry.
///
/// The integral is computed deterministically in the model's sample space: (u1, u2) ∈ [0,1)² mapped
/// by PolarizedBrdf::sample, whose weight is M·cosθi/pdf, so ∫ M e0 cosθi dωi = ∫∫ weight·e0 du1
/// du2. Composite Gauss–Legendre rules in u1 (split at sample_u1_breaks, so every piece maps
/// smoothly) and u2 follow the lobe however narrow it is, and delta lobes are exact (their weight
/// is the reflectance matrix). Isotropic models (PolarizedBrdf::is_isotropic) are integrated over
/// half the azimuths. Accuracy (tests/materials/emissivity_test.cpp): |Δε| < 2e-4 against a
/// brute-force 2-D integration over the hemisphere for rough surfaces, and exact (1e-12) for smooth
/// ones.
///
/// Emissivity tables (emissivity.h) cached in memory for the life of the process and on disk across
/// processes. A table is keyed by what determines it: the model name, its parameters (n, k, σ, …)
/// at every wavelength of the table, the wavelengths themselves (the spectral grid of a band), the
/// angle grid, the integrator options and kEmissivityCacheVersion. So editing a material file or
/// choosing another band or grid selects another entry; nothing is ever looked up by name alone.
///
/// Disk entries live in one folder, one file per table (`<model>-<128-bit key>.emtab`), written
/// atomically (core atomic_file.h). A file is trusted only if its magic, version, key, wavelengths,
/// sizes, finite values and checksum all match; otherwise it is rebuilt and overwritten. A folder
/// that cannot be written only costs the rebuild (a warning is logged), never a failed render.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "tirpol/core/radiometry.h"
#include "tirpol/core/stokes.h"
#include "tirpol/materials/pbrdf.h"

namespace tirpol::materials {

struct EmissivityOptions {
    int radial_panels = 12;  ///< Gauss–Legendre panels along u1, per lobe piece
    int azimuth_panels = 8;  ///< Gauss–Legendre panels along u2
    int order = 6;           ///< Gauss–Legendre nodes per panel (1..10)
};

/// ∫ M(wi→wo)·e0 cosθi dωi for wo at polar angle acos(cos_theta) (φo = 0): the Stokes vector
/// reflected towards wo under uniform unpolarized unit radiance. S0 is the DHR. cos_theta is
/// clamped to [kMinCosine, 1] so that exactly grazing views get the grazing limit.
StokesVector hemispherical_reflected_stokes(const PolarizedBrdf& brdf, double cos_theta,
                                            double wavelength_um,
                                            const EmissivityOptions& options = {});

/// Polarized directional emissivity ε = e0 − hemispherical_reflected_stokes (file comment).
StokesVector directional_emissivity(const PolarizedBrdf& brdf, double cos_theta,
                                    double wavelength_um, const EmissivityOptions& options = {});

/// Directional-hemispherical reflectance ρ_DHR(θ) (paper eq 2), = 1 − ε_S0.
double directional_hemispherical_reflectance(const PolarizedBrdf& brdf, double cos_theta,
                                             double wavelength_um,
                                             const EmissivityOptions& options = {});

/// Emissivity tabulated over emission angle θ ∈ [0°, 90°] and a list of wavelengths, for per-hit
/// lookups by the renderer. The θ nodes are θj = 90°·(1 − (1 − j/(N−1))²): twice as sparse as
/// uniform at normal incidence and ever denser towards 90° (last step 90°/(N−1)²), where ε and DoLP
/// change fastest. Lookups use cubic Lagrange interpolation on that grid (no allocation, no
/// exceptions).
class EmissivityTable {
public:
    /// Builds the table. Throws tirpol::Error if a wavelength lies outside the model's
    /// valid_wavelength_range_um, or if the list is empty / not increasing. Wavelengths at which
    /// the model's parameters are identical to the previous wavelength's reuse that column. The
    /// integrals run on up to std::thread::hardware_concurrency() threads.
    EmissivityTable(const PolarizedBrdf& brdf, std::vector<double> wavelengths_um,
                    int angle_nodes = 65, const EmissivityOptions& options = {});

    /// A table from stored node values (emissivity_cache.h), laid out as
    /// values()[wavelength][angle] on the same angle grid as a built table with `angle_nodes`
    /// nodes. Throws tirpol::Error if the sizes disagree, the wavelengths do not increase or a
    /// value is not finite.
    static EmissivityTable from_values(std::vector<double> wavelengths_um, int angle_nodes,
                                       std::vector<StokesVector> values);

    /// Emissivity Stokes vector at cos θ (clamped to [0, 1]) for the table's wavelength index.
    StokesVector at(double cos_theta, std::size_t wavelength_index) const;

    /// Emissivity at an arbitrary wavelength: linear in wavelength between columns, clamped at the
    /// ends. Between columns this is not Kirchhoff-consistent with a reflection evaluated at that
    /// wavelength; a renderer that needs ε + ρ = 1 per path samples the table's own wavelengths and
    /// calls `at`.
    StokesVector at_wavelength(double cos_theta, double wavelength_um) const;

    /// Planck×RSR-weighted band average ∫R L_bb(T) ε dλ / ∫R L_bb(T) dλ over the band's quadrature
    /// nodes (radiometry.h), with ε interpolated in wavelength as in at_wavelength. No allocation;
    /// it evaluates Planck at every band node, so hot loops with a fixed (band, T) should use
    /// band_weights once and at_weighted per hit (same result).
    StokesVector band_average(double cos_theta, const Band& band, double temperature_k) const;

    /// Normalised per-column weights w_j with band_average(θ) = Σ_j w_j·at(θ, j).
    std::vector<double> band_weights(const Band& band, double temperature_k) const;

    /// Σ_j weights[j]·at(cos θ, j) (weights from band_weights; one entry per wavelength). No
    /// allocation.
    StokesVector at_weighted(double cos_theta, const std::vector<double>& weights) const;

    const std::vector<double>& wavelengths_um() const { return m_wavelengths_um; }
    /// Every node value, [wavelength][angle] (for storing the table).
    const std::vector<StokesVector>& values() const { return m_values; }
    /// Emission angles of the nodes, radians.
    const std::vector<double>& angles_rad() const { return m_angles_rad; }
    /// The value stored at node (angle_index, wavelength_index).
    const StokesVector& node(std::size_t angle_index, std::size_t wavelength_index) const {
        return m_values[wavelength_index * m_angles_rad.size() + angle_index];
    }

    /// Wavelengths spanning a band (its ends and steps of at most `step_um`), for building a table.
    static std::vector<double> wavelengths_for_band(const Band& band, double step_um = 0.5);

private:
    EmissivityTable() = default;
    /// Checks the wavelength list and sets the angle nodes.
    void init_grid(int angle_nodes);
    /// Cubic interpolation at grid coordinate p ∈ [0, N−1] for one column.
    StokesVector at_position(double p, std::size_t wavelength_index) const;
    double position(double cos_theta) const;

    std::vector<double> m_wavelengths_um;
    std::vector<double> m_angles_rad;
    std::vector<StokesVector> m_values;  // [wavelength][angle]
};

/// Bump when the emissivity integrator or a model's sampling changes the numbers a table holds.
inline constexpr int kEmissivityCacheVersion = 1;

/// Where a cached table came from.
enum class EmissivityCacheSource {
    memory,           ///< already built or loaded by this process
    disk,             ///< read from a valid cache file
    built,            ///< computed (no cache file, or no cache folder)
    rebuilt_corrupt,  ///< computed because the cache file was invalid; the file was replaced
};

struct CachedEmissivityTable {
    std::shared_ptr<const EmissivityTable> table;
    EmissivityCacheSource source = EmissivityCacheSource::built;
};

/// The disk cache folder: $TIRPOL_CACHE_DIR if set, else $XDG_CACHE_HOME/tirpol (absolute paths
/// only, per the XDG base-directory specification), else $HOME/.cache/tirpol; empty if none
/// applies.
std::filesystem::path default_emissivity_cache_directory();

/// Hex key of the table `EmissivityTable(brdf, wavelengths_um, angle_nodes, options)` would hold
/// (file comment). Deterministic across processes and machines of the same endianness.
std::string emissivity_table_key(const PolarizedBrdf& brdf,
                                 const std::vector<double>& wavelengths_um, int angle_nodes = 65,
                                 const EmissivityOptions& options = {});

/// The table for `brdf` at `wavelengths_um`: from this process's memory, else from `directory`,
/// else built (and stored in both). An empty `directory` keeps the cache in memory only.
/// Thread-safe. Throws what EmissivityTable's constructor throws.
CachedEmissivityTable cached_emissivity_table(const PolarizedBrdf& brdf,
                                              const std::vector<double>& wavelengths_um,
                                              const std::filesystem::path& directory,
                                              int angle_nodes = 65,
                                              const EmissivityOptions& options = {});

/// Forgets every table held in memory (tests; long-running processes that reload materials need not
/// call it, since a changed material has another key).
void clear_emissivity_memory_cache();

}  // namespace tirpol::materials
