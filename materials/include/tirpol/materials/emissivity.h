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
///
/// Polarized emissivity versus emission angle for one material, as a table (CSV) and a plot like
/// the paper's Fig. 1 (ε_S0 and ε_S1 against angle), at one wavelength or averaged over a band.
///
/// `tirpol emissivity`: a material's polarized emissivity versus emission angle at one wavelength
/// or over a band, written as CSV and plot when asked, and reported as JSON or a text table.

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
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

struct EmissivityRow {
    double angle_deg = 0.0;  ///< emission angle from the surface normal
    StokesVector e =
        StokesVector::Zero();  ///< ε as Stokes in the s/p frame (S1 < 0: in the plane of emission)
    double dolp = 0.0;         ///< degree of linear polarization of the emission
    double dhr = 0.0;          ///< directional-hemispherical reflectance 1 − ε_S0
};

/// Parses an angle list "0,45,60" or an inclusive range "START:STOP:STEP" (degrees, within [0,
/// 90]). Throws tirpol::Error naming the specification and what was expected.
std::vector<double> parse_angles_deg(const std::string& spec);

/// ε at one wavelength, integrated directly at every angle.
std::vector<EmissivityRow> emissivity_curve(const PolarizedBrdf& brdf,
                                            const std::vector<double>& angles_deg,
                                            double wavelength_um);

/// Planck(T)×RSR-weighted band average, from an EmissivityTable over the band (0.25 µm steps).
/// Throws if the band leaves the model's data range.
std::vector<EmissivityRow> emissivity_curve(const PolarizedBrdf& brdf,
                                            const std::vector<double>& angles_deg, const Band& band,
                                            double temperature_k);

/// CSV text with header angle_deg,e_s0,e_s1,e_s2,e_s3,dolp,dhr.
std::string emissivity_csv(const std::vector<EmissivityRow>& rows);

/// PNG plot of ε_S0 and ε_S1 against emission angle (paper Fig. 1 layout).
void write_emissivity_plot(const std::filesystem::path& path,
                           const std::vector<EmissivityRow>& rows, const std::string& title);

/// What to compute: at wavelength_um when set, else over band_um (RSR file rsr, "" = flat)
/// weighted by Planck at temperature_k; csv and plot are written when not empty.
struct EmissivityReportOptions {
    std::string material;  ///< YAML file or library name (material_file)
    std::vector<double> angles_deg;
    std::optional<double> wavelength_um;
    std::array<double, 2> band_um{};
    std::string rsr;
    double temperature_k = 300.0;
    std::string csv;     ///< CSV table to write (emissivity_csv), or ""
    std::string plot;    ///< PNG plot to write (write_emissivity_plot), or ""
    bool force = false;  ///< existing outputs may be replaced (OutputGuard)
};

/// The result of emissivity_report.
struct EmissivityReport {
    EmissivityReportOptions options;
    std::string material;  ///< the material's name
    std::string model;     ///< its pBRDF model
    std::string spectral;  ///< "10 µm" or "8–14 µm band at 300 K"
    std::vector<EmissivityRow> rows;
};

/// Checks the outputs against the inputs (OutputGuard: OutputConflict before any work), loads the
/// material, computes the curve and writes the CSV and plot asked for. Throws
/// tirpol::OptionValueError naming --temperature-k for a band's temperature not above 0 K, and
/// tirpol::Error for a material that does not load, a wavelength or band outside its data or an
/// RSR file that does not read.
EmissivityReport emissivity_report(const EmissivityReportOptions& options);

/// The JSON report (docs/materials.md): material, file, model, wavelength_um or band_um, rsr and
/// temperature_k, and rows (angle_deg, e_s0…e_s3, dolp, dhr).
nlohmann::json emissivity_report_json(const EmissivityReport& report);

/// The text table with a heading, and the paths of the files written.
std::string emissivity_report_text(const EmissivityReport& report);

}  // namespace tirpol::materials
