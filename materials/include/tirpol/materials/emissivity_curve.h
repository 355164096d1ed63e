#pragma once
/// \file emissivity_curve.h
/// Polarized emissivity versus emission angle for one material, as a table (CSV) and a plot like
/// the paper's Fig. 1 (ε_S0 and ε_S1 against angle), at one wavelength or averaged over a band.
///
/// `tirpol emissivity`: a material's polarized emissivity versus emission angle at one wavelength
/// or over a band, written as CSV and plot when asked, and reported as JSON or a text table.

#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/core/radiometry.h"
#include "tirpol/core/stokes.h"
#include "tirpol/materials/pbrdf.h"

namespace tirpol::materials {

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
