#include <sstream>

#include "tirpol/core/error.h"
#include "tirpol/fitting/fit_run.h"
#include "tirpol/fitting/microfacet_fit.h"
#include "tirpol/materials/material.h"

namespace tirpol::fitting {

namespace {

using P = MicrofacetParameter;

std::string plus_minus(const FittedParameter& f) {
    if (f.fixed) return fmt::format("{} = {:.6g} (fixed)", f.name, f.value);
    return fmt::format("{} = {:.6g} ± {:.2g} (2σ){}", f.name, f.value, 2.0 * f.std_uncertainty,
                       f.at_bound ? " [at bound]" : "");
}

std::string free_names(const MicrofacetFitResult& r) {
    std::string out;
    for (std::size_t i : r.free_indices) out += (out.empty() ? "" : " ") + r.parameters[i].name;
    return out;
}

std::string join(const std::vector<std::string>& items, const std::string& separator) {
    std::string out;
    for (const auto& s : items) out += (out.empty() ? "" : separator) + s;
    return out;
}

}  // namespace

std::string fitted_material_yaml(const std::string& name, const MicrofacetFitResult& r,
                                 const FitProvenance& provenance) {
    materials::MicrofacetMaterialRecord m;
    m.name = name;
    auto& comments = m.comment_lines;
    comments.push_back(
        "Fitted by `tirpol fit` (docs/fitting.md): micro-facet pBRDF parameters from measured "
        "polarized");
    comments.push_back(
        "emissivity by weighted least squares (Ceres), uncertainties from the covariance at the "
        "minimum.");
    comments.push_back("data: " + join(provenance.data_files, ", "));
    comments.push_back("date: " + provenance.date_utc);
    if (!provenance.command.empty()) comments.push_back("command: " + provenance.command);
    comments.push_back(fmt::format("chi2 = {:.4g}, dof = {}, chi2/dof = {:.4g}{}; termination: {}",
                                   r.chi2, r.dof, r.reduced_chi2,
                                   r.covariance_scaled ? " (covariance scaled by chi2/dof)" : "",
                                   r.termination));
    comments.push_back(fmt::format("starts: {}, fraction reaching the best minimum: {:.2f}",
                                   r.starts.size(), r.fraction_reaching_best));
    if (r.covariance_available) {
        comments.push_back("correlation of the free parameters (" + free_names(r) + "):");
        for (Eigen::Index i = 0; i < r.correlation.rows(); ++i) {
            std::string row = " ";
            for (Eigen::Index j = 0; j < r.correlation.cols(); ++j)
                row += fmt::format(" {:+.3f}", r.correlation(i, j));
            comments.push_back(row);
        }
    }
    comments.push_back("residuals per angle, (model - measured)/sigma for eps_S0 and eps_S1:");
    for (const SampleFit& s : r.samples)
        comments.push_back(fmt::format("  dataset {} angle {:5.1f} deg: {:+.2f} {:+.2f}", s.dataset,
                                       s.angle_deg, s.residual_s0, s.residual_s1));

    m.source =
        fmt::format("tirpol fit of {} on {}: micro-facet model, chi2/dof = {:.3g} (dof {}), {}",
                    join(provenance.data_files, ", "), provenance.date_utc, r.reduced_chi2, r.dof,
                    r.usable ? "converged" : "NOT CONVERGED");
    std::vector<std::string> notes;
    for (const FittedParameter& f : r.parameters) notes.push_back(plus_minus(f));
    m.notes =
        "Fitted values: " + join(notes, "; ") + ". Termination: " + r.termination.text() + ".";
    if (!r.warnings.empty()) m.notes += " Warnings: " + join(r.warnings, " | ");
    m.wavelengths_um = r.wavelengths_um;
    for (std::size_t band = 0; band < r.wavelengths_um.size(); ++band) {
        m.n.push_back(r.get(P::n, band).value);
        m.k.push_back(r.get(P::k, band).value);
    }
    m.sigma = r.get(P::sigma).value;
    m.bias = r.get(P::bias).value;
    m.tau_deg = r.get(P::tau_deg).value;
    m.omega_deg = r.get(P::omega_deg).value;
    m.rho_d = r.get(P::rho_d).value;
    m.rho_v = r.get(P::rho_v).value;
    return materials::microfacet_material_yaml(m);
}

nlohmann::json fit_report_json(const MicrofacetFitResult& r,
                               const std::vector<EmissivityDataset>& datasets,
                               const FitProvenance& provenance) {
    nlohmann::json j;
    j["model"] = "micro-facet";
    j["data_files"] = provenance.data_files;
    j["date_utc"] = provenance.date_utc;
    j["command"] = provenance.command;
    j["termination"] = r.termination.text();
    j["usable"] = r.usable;
    j["solver_report"] = r.solver_report;
    j["chi2"] = r.chi2;
    j["dof"] = r.dof;
    j["reduced_chi2"] = r.reduced_chi2;
    j["covariance_available"] = r.covariance_available;
    j["covariance_scaled"] = r.covariance_scaled;
    j["wavelengths_um"] = r.wavelengths_um;
    nlohmann::json params = nlohmann::json::array();
    for (const FittedParameter& f : r.parameters) {
        nlohmann::json p{{"name", f.name},        {"value", f.value},
                         {"fixed", f.fixed},      {"sigma", f.std_uncertainty},
                         {"lower", f.lower},      {"upper", f.upper},
                         {"at_bound", f.at_bound}};
        if (!f.fixed) {
            const ParameterInterval interval = interval_2sigma(f);
            p["interval_2sigma"] = {interval.lower, interval.upper};
        }
        if (f.wavelength_um) p["wavelength_um"] = *f.wavelength_um;
        params.push_back(p);
    }
    j["parameters"] = params;
    std::vector<std::string> names;
    for (std::size_t i : r.free_indices) names.push_back(r.parameters[i].name);
    nlohmann::json corr = nlohmann::json::array();
    for (Eigen::Index i = 0; i < r.correlation.rows(); ++i) {
        std::vector<double> row;
        for (Eigen::Index c = 0; c < r.correlation.cols(); ++c) row.push_back(r.correlation(i, c));
        corr.push_back(row);
    }
    j["correlation"] = {{"names", names}, {"matrix", corr}};
    nlohmann::json samples = nlohmann::json::array();
    for (const SampleFit& s : r.samples) {
        const EmissivitySample& m = datasets.at(s.dataset).samples.at(s.sample);
        samples.push_back({{"dataset", s.dataset},
                           {"wavelength_um", datasets[s.dataset].wavelength_um},
                           {"angle_deg", s.angle_deg},
                           {"measured_s0", m.eps_s0},
                           {"sigma_s0", m.eps_s0_std},
                           {"model_s0", s.model_s0},
                           {"residual_s0", s.residual_s0},
                           {"measured_s1", m.eps_s1},
                           {"sigma_s1", m.eps_s1_std},
                           {"model_s1", s.model_s1},
                           {"residual_s1", s.residual_s1}});
    }
    j["samples"] = samples;
    nlohmann::json starts = nlohmann::json::array();
    for (const StartOutcome& s : r.starts)
        starts.push_back({{"initial", s.initial},
                          {"chi2", s.chi2},
                          {"usable", s.usable},
                          {"iterations", s.iterations},
                          {"reached_best", s.reached_best},
                          {"termination", s.termination.text()}});
    j["starts"] = {{"count", r.starts.size()},
                   {"fraction_reaching_best", r.fraction_reaching_best},
                   {"outcomes", starts}};
    j["evaluations"] = {{"residual", r.residual_evaluations}, {"jacobian", r.jacobian_evaluations}};
    j["warnings"] = r.warnings;
    return j;
}

std::string fit_report_text(const MicrofacetFitResult& r,
                            const std::vector<EmissivityDataset>& datasets) {
    std::ostringstream out;
    out << fmt::format("termination: {}{}\n", r.termination, r.usable ? "" : "  (NOT USABLE)");
    out << fmt::format("chi2 = {:.4g}, dof = {}, chi2/dof = {:.4g}{}\n", r.chi2, r.dof,
                       r.reduced_chi2,
                       r.covariance_scaled ? " (covariance scaled by chi2/dof)" : "");
    out << fmt::format("starts: {}, reaching the best minimum: {:.0f}%\n", r.starts.size(),
                       100.0 * r.fraction_reaching_best);
    out << "parameter          value        2σ interval\n";
    for (const FittedParameter& f : r.parameters) {
        if (f.fixed) {
            out << fmt::format("  {:<14} {:>12.6g}   (fixed)\n", f.name, f.value);
        } else {
            const ParameterInterval interval = interval_2sigma(f);
            out << fmt::format("  {:<14} {:>12.6g}   [{:.6g}, {:.6g}]{}{}\n", f.name, f.value,
                               interval.lower, interval.upper, f.at_bound ? "  at bound" : "",
                               interval.clipped ? "  (cut at the bounds)" : "");
        }
    }
    if (r.covariance_available && r.free_indices.size() > 1) {
        out << "correlation (" << free_names(r) << "):\n";
        for (Eigen::Index i = 0; i < r.correlation.rows(); ++i) {
            out << " ";
            for (Eigen::Index j = 0; j < r.correlation.cols(); ++j)
                out << fmt::format(" {:+.3f}", r.correlation(i, j));
            out << '\n';
        }
    }
    out << "angle   eps_S0 meas   model   resid | eps_S1 meas   model   resid\n";
    for (const SampleFit& s : r.samples) {
        const EmissivitySample& m = datasets.at(s.dataset).samples.at(s.sample);
        out << fmt::format("{:5.1f}   {:9.4f} {:9.4f} {:+6.2f}  | {:9.4f} {:9.4f} {:+6.2f}\n",
                           s.angle_deg, m.eps_s0, s.model_s0, s.residual_s0, m.eps_s1, s.model_s1,
                           s.residual_s1);
    }
    for (const std::string& w : r.warnings) out << "warning: " << w << '\n';
    return out.str();
}

}  // namespace tirpol::fitting
