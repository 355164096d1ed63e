#include <fmt/printf.h>

#include <cmath>

#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/materials/emissivity.h"
#include "tirpol/materials/material.h"

namespace tirpol::materials {

EmissivityReport emissivity_report(const EmissivityReportOptions& o) {
    OutputGuard()
        .input(o.material, "MATERIAL")
        .input(o.rsr, "--rsr")
        .output_file(o.csv, "--csv")
        .output_file(o.plot, "--plot")
        .check(o.force);
    if (!o.wavelength_um && !(o.temperature_k > 0.0))
        throw OptionValueError(
            "--temperature-k",
            fmt::format("expected a temperature above 0 K, got {}", o.temperature_k));
    const Material m = load_material(material_file(o.material));
    EmissivityReport report{o, m.name, m.brdf->model(), "", {}};
    std::string spectral_ascii;  // the plot's Hershey font has no µ or en dash
    if (o.wavelength_um) {
        report.rows = emissivity_curve(*m.brdf, o.angles_deg, *o.wavelength_um);
        report.spectral = fmt::format("{} µm", *o.wavelength_um);
        spectral_ascii = fmt::format("{} um", *o.wavelength_um);
    } else {
        std::optional<SpectralResponse> rsr;
        if (!o.rsr.empty()) rsr = SpectralResponse::load_csv(o.rsr);
        const Band band(o.band_um[0], o.band_um[1], rsr);
        report.rows = emissivity_curve(*m.brdf, o.angles_deg, band, o.temperature_k);
        report.spectral =
            fmt::format("{}–{} µm band at {} K", o.band_um[0], o.band_um[1], o.temperature_k);
        spectral_ascii =
            fmt::format("{}-{} um band at {} K", o.band_um[0], o.band_um[1], o.temperature_k);
    }
    if (!o.csv.empty()) write_file_atomic(o.csv, emissivity_csv(report.rows));
    if (!o.plot.empty()) write_emissivity_plot(o.plot, report.rows, m.name + ", " + spectral_ascii);
    return report;
}

nlohmann::json emissivity_report_json(const EmissivityReport& r) {
    nlohmann::json out;
    out["material"] = r.material;
    out["file"] = r.options.material;
    out["model"] = r.model;
    if (r.options.wavelength_um) {
        out["wavelength_um"] = *r.options.wavelength_um;
    } else {
        out["band_um"] = r.options.band_um;
        out["rsr"] =
            r.options.rsr.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.options.rsr);
        out["temperature_k"] = r.options.temperature_k;
    }
    nlohmann::json rows = nlohmann::json::array();
    for (const auto& row : r.rows)
        rows.push_back({{"angle_deg", row.angle_deg},
                        {"e_s0", row.e(0)},
                        {"e_s1", row.e(1)},
                        {"e_s2", row.e(2)},
                        {"e_s3", row.e(3)},
                        {"dolp", row.dolp},
                        {"dhr", row.dhr}});
    out["rows"] = rows;
    return out;
}

std::string emissivity_report_text(const EmissivityReport& r) {
    std::string text = fmt::sprintf(
        "%s (%s), %s; Stokes in the s/p frame, S1 < 0 = polarized in the plane of emission\n",
        r.material, r.model, r.spectral);
    text += fmt::sprintf("%9s %9s %9s %9s %9s %8s %8s\n", "angle_deg", "e_s0", "e_s1", "e_s2",
                         "e_s3", "dolp", "dhr");
    // Rounding noise of symmetric integrals (|x| ~ 1e-17) would print as "-0.00000".
    const auto shown = [](double x) { return std::abs(x) < 5e-7 ? 0.0 : x; };
    for (const auto& row : r.rows)
        text += fmt::sprintf("%9.2f %9.5f %9.5f %9.5f %9.5f %8.5f %8.5f\n", row.angle_deg, row.e(0),
                             shown(row.e(1)), shown(row.e(2)), shown(row.e(3)), shown(row.dolp),
                             row.dhr);
    if (!r.options.csv.empty()) text += fmt::sprintf("table: %s\n", r.options.csv);
    if (!r.options.plot.empty()) text += fmt::sprintf("plot:  %s\n", r.options.plot);
    return text;
}

}  // namespace tirpol::materials
