#pragma once
/// \file emissivity_report.h
/// `tirpol emissivity`: a material's polarized emissivity versus emission angle at one wavelength
/// or over a band, written as CSV and plot when asked, and reported as JSON or a text table.

#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/materials/emissivity_curve.h"

namespace tirpol::materials {

/// What to compute: at wavelength_um when set, else over band_um (RSR file rsr, "" = flat)
/// weighted by Planck at temperature_k; csv and plot are written when not empty.
struct EmissivityReportOptions {
    std::string material;  ///< YAML file or library name (material_file)
    std::vector<double> angles_deg;
    std::optional<double> wavelength_um;
    std::array<double, 2> band_um{};
    std::string rsr;
    double temperature_k = 300.0;
    std::string csv;   ///< CSV table to write (emissivity_csv), or ""
    std::string plot;  ///< PNG plot to write (write_emissivity_plot), or ""
};

/// The result of emissivity_report.
struct EmissivityReport {
    EmissivityReportOptions options;
    std::string material;  ///< the material's name
    std::string model;     ///< its pBRDF model
    std::string spectral;  ///< "10 µm" or "8–14 µm band at 300 K"
    std::vector<EmissivityRow> rows;
};

/// Loads the material, computes the curve and writes the CSV and plot asked for. Throws
/// tirpol::Error for a material that does not load, a wavelength or band outside its data, a
/// temperature not above 0 K or an RSR file that does not read.
EmissivityReport emissivity_report(const EmissivityReportOptions& options);

/// The JSON report (docs/materials.md): material, file, model, wavelength_um or band_um, rsr and
/// temperature_k, and rows (angle_deg, e_s0…e_s3, dolp, dhr).
nlohmann::json emissivity_report_json(const EmissivityReport& report);

/// The text table with a heading, and the paths of the files written.
std::string emissivity_report_text(const EmissivityReport& report);

}  // namespace tirpol::materials
