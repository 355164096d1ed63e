// tirpol.fitting: the Ceres fit of micro-facet pBRDF parameters to polarized emissivity given as
// numpy arrays, returning a FitResult with estimates, covariance and 2σ intervals.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "interruptible.h"
#include "tirpol/core/error.h"
#include "tirpol/fitting/microfacet_fit.h"

namespace py = pybind11;

namespace tirpol::python {

namespace {

using namespace tirpol::fitting;
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::vector<double> values_of(const DoubleArray& a, const char* what, std::size_t expected) {
    if (a.ndim() != 1) fail("{}: expected a 1-D array, got {} dimensions", what, a.ndim());
    if (expected != 0 && static_cast<std::size_t>(a.size()) != expected)
        fail("{}: {} values, but angle_deg has {}", what, a.size(), expected);
    return {a.data(), a.data() + a.size()};
}

/// Applies {"sigma": {"initial": 0.3, "lower": 0.05, "upper": 1, "fixed": False}, ...} to the
/// defaults.
void apply_parameter_settings(const py::dict& settings, MicrofacetFitOptions& options) {
    for (const auto& [key, value] : settings) {
        const auto name = key.cast<std::string>();
        ParameterSetting& s =
            options.parameters[static_cast<std::size_t>(parameter_from_name(name))];
        for (const auto& [field, v] : value.cast<py::dict>()) {
            const auto f = field.cast<std::string>();
            if (f == "initial")
                s.initial = v.cast<double>();
            else if (f == "lower")
                s.lower = v.cast<double>();
            else if (f == "upper")
                s.upper = v.cast<double>();
            else if (f == "fixed")
                s.fixed = v.cast<bool>();
            else
                fail("parameters['{}']: unknown field '{}' (expected initial, lower, upper, fixed)",
                     name, f);
        }
    }
}

struct FitResult {
    MicrofacetFitResult result;

    py::dict estimates() const {
        py::dict out;
        for (const auto& p : result.parameters) out[py::str(p.name)] = p.value;
        return out;
    }
    py::dict sigmas() const {
        py::dict out;
        for (const auto& p : result.parameters) out[py::str(p.name)] = p.std_uncertainty;
        return out;
    }
    /// value ± 2σ for the free parameters, clipped to their bounds (as the CLI prints them).
    py::dict intervals_2sigma() const {
        py::dict out;
        for (std::size_t i : result.free_indices) {
            const auto& p = result.parameters[i];
            const fitting::ParameterInterval interval = fitting::interval_2sigma(p);
            out[py::str(p.name)] = py::make_tuple(interval.lower, interval.upper);
        }
        return out;
    }
    std::vector<std::string> free_names() const {
        std::vector<std::string> names;
        for (std::size_t i : result.free_indices) names.push_back(result.parameters[i].name);
        return names;
    }
};

void bind_fit_result(py::module_& m) {
    py::class_<FitResult>(
        m, "FitResult",
        "Outcome of fit_microfacet: estimates, standard uncertainties, covariance of the free "
        "parameters and 2σ intervals, χ², and what the solver said.")
        .def_property_readonly("estimates", &FitResult::estimates,
                               "Every parameter (free and fixed): name → value.")
        .def_property_readonly("sigmas", &FitResult::sigmas,
                               "Standard uncertainty per parameter (0 when fixed).")
        .def_property_readonly(
            "intervals_2sigma", &FitResult::intervals_2sigma,
            "Free parameters: name → (value − 2σ, value + 2σ), clipped to the bounds.")
        .def_property_readonly("free_names", &FitResult::free_names,
                               "Order of the covariance rows and columns.")
        .def_property_readonly("covariance", [](const FitResult& r) { return r.result.covariance; })
        .def_property_readonly("correlation",
                               [](const FitResult& r) { return r.result.correlation; })
        .def_property_readonly("covariance_available",
                               [](const FitResult& r) { return r.result.covariance_available; })
        .def_property_readonly("at_bound",
                               [](const FitResult& r) {
                                   std::vector<std::string> names;
                                   for (const auto& p : r.result.parameters)
                                       if (p.at_bound && !p.fixed) names.push_back(p.name);
                                   return names;
                               })
        .def_property_readonly("chi2", [](const FitResult& r) { return r.result.chi2; })
        .def_property_readonly("dof", [](const FitResult& r) { return r.result.dof; })
        .def_property_readonly("reduced_chi2",
                               [](const FitResult& r) { return r.result.reduced_chi2; })
        .def_property_readonly("usable", [](const FitResult& r) { return r.result.usable; })
        .def_property_readonly("termination",
                               [](const FitResult& r) { return r.result.termination.text(); })
        .def_property_readonly("warnings", [](const FitResult& r) { return r.result.warnings; })
        .def_property_readonly("model_e_s0",
                               [](const FitResult& r) {
                                   std::vector<double> v;
                                   for (const auto& s : r.result.samples) v.push_back(s.model_s0);
                                   return v;
                               })
        .def_property_readonly("model_e_s1",
                               [](const FitResult& r) {
                                   std::vector<double> v;
                                   for (const auto& s : r.result.samples) v.push_back(s.model_s1);
                                   return v;
                               })
        .def("__repr__", [](const FitResult& r) {
            return fmt::format("<tirpol.fitting.FitResult chi2/dof={:.3g} usable={} free={}>",
                               r.result.reduced_chi2, r.result.usable,
                               r.result.free_indices.size());
        });
}

/// One dataset from 1-D arrays of equal length.
EmissivityDataset dataset_of(const DoubleArray& angle_deg, const DoubleArray& e_s0,
                             const DoubleArray& e_s0_sigma, const DoubleArray& e_s1,
                             const DoubleArray& e_s1_sigma, double wavelength_um,
                             std::string source) {
    const auto angles = values_of(angle_deg, "angle_deg", 0);
    const auto s0 = values_of(e_s0, "e_s0", angles.size()),
               s0_sigma = values_of(e_s0_sigma, "e_s0_sigma", angles.size());
    const auto s1 = values_of(e_s1, "e_s1", angles.size()),
               s1_sigma = values_of(e_s1_sigma, "e_s1_sigma", angles.size());
    EmissivityDataset dataset;
    dataset.source = std::move(source);
    dataset.wavelength_um = wavelength_um;
    for (std::size_t i = 0; i < angles.size(); ++i)
        dataset.samples.push_back({angles[i], s0[i], s0_sigma[i], s1[i], s1_sigma[i], ""});
    return dataset;
}

/// Validates, then solves on a worker thread that Ctrl-C stops (MicrofacetFitOptions::cancel).
FitResult solve(std::vector<EmissivityDataset> datasets, const py::dict& parameters, int starts,
                std::uint64_t seed, bool scale_covariance_by_reduced_chi2) {
    MicrofacetFitOptions options;
    apply_parameter_settings(parameters, options);
    options.starts = starts;
    options.seed = seed;
    options.scale_covariance_by_reduced_chi2 = scale_covariance_by_reduced_chi2;
    return run_interruptible([&](const std::atomic<bool>& cancel) {
        MicrofacetFitOptions o = options;
        o.cancel = &cancel;
        return FitResult{MicrofacetFitProblem(std::move(datasets), o).solve()};
    });
}

void bind_fit(py::module_& m) {
    m.def(
        "fit_microfacet",
        [](const DoubleArray& angle_deg, const DoubleArray& e_s0, const DoubleArray& e_s0_sigma,
           const DoubleArray& e_s1, const DoubleArray& e_s1_sigma, double wavelength_um,
           const py::dict& parameters, int starts, std::uint64_t seed,
           bool scale_covariance_by_reduced_chi2) {
            return solve({dataset_of(angle_deg, e_s0, e_s0_sigma, e_s1, e_s1_sigma, wavelength_um,
                                     "arrays from Python")},
                         parameters, starts, seed, scale_covariance_by_reduced_chi2);
        },
        py::arg("angle_deg"), py::arg("e_s0"), py::arg("e_s0_sigma"), py::arg("e_s1"),
        py::arg("e_s1_sigma"), py::arg("wavelength_um") = 10.0, py::arg("parameters") = py::dict(),
        py::arg("starts") = 16, py::arg("seed") = 1,
        py::arg("scale_covariance_by_reduced_chi2") = false,
        "Weighted least-squares fit of the micro-facet pBRDF (n, k, sigma, bias, tau_deg, "
        "omega_deg, rho_d, rho_v) "
        "to polarized emissivity ε_S0(θ), ε_S1(θ) (1-D arrays, 1σ uncertainties; ε_S1 in the "
        "plane-of-emission "
        "frame, < 0 for emission polarized in it) with Ceres, several starts (docs/fitting.md). "
        "`parameters` "
        "overrides the defaults per name: {'sigma': {'initial': 0.3, 'lower': 0.05, 'upper': 1, "
        "'fixed': False}}. "
        "Releases the GIL; Ctrl-C stops it at the next solver iteration (KeyboardInterrupt).");
    m.def(
        "fit_microfacet_joint",
        [](const py::list& datasets, const py::dict& parameters, int starts, std::uint64_t seed,
           bool scale_covariance_by_reduced_chi2) {
            std::vector<EmissivityDataset> inputs;
            for (const auto& item : datasets) {
                const auto d = item.cast<py::dict>();
                const std::string source = fmt::format("datasets[{}]", inputs.size());
                for (const char* key :
                     {"angle_deg", "e_s0", "e_s0_sigma", "e_s1", "e_s1_sigma", "wavelength_um"})
                    if (!d.contains(key))
                        fail(
                            "{}: no '{}' (expected angle_deg, e_s0, e_s0_sigma, e_s1, e_s1_sigma, "
                            "wavelength_um)",
                            source, key);
                inputs.push_back(
                    dataset_of(d["angle_deg"].cast<DoubleArray>(), d["e_s0"].cast<DoubleArray>(),
                               d["e_s0_sigma"].cast<DoubleArray>(), d["e_s1"].cast<DoubleArray>(),
                               d["e_s1_sigma"].cast<DoubleArray>(),
                               d["wavelength_um"].cast<double>(), source));
            }
            if (inputs.empty()) fail("datasets: none given (expected a list of dicts of arrays)");
            return solve(std::move(inputs), parameters, starts, seed,
                         scale_covariance_by_reduced_chi2);
        },
        py::arg("datasets"), py::arg("parameters") = py::dict(), py::arg("starts") = 16,
        py::arg("seed") = 1, py::arg("scale_covariance_by_reduced_chi2") = false,
        "Joint fit of several datasets of one material — view-angle series or wavelength bands, "
        "each a dict with "
        "the arrays angle_deg, e_s0, e_s0_sigma, e_s1, e_s1_sigma and a number wavelength_um: σ, "
        "bias, τ, Ω, ρ_D, "
        "ρ_V are shared, n and k are fitted per distinct wavelength (named 'n@8.5um', 'k@8.5um' "
        "when there are "
        "several). model_e_s0/model_e_s1 list the samples of all datasets in order. Releases the "
        "GIL; Ctrl-C stops "
        "it (KeyboardInterrupt).");
}

}  // namespace

void bind_fitting(py::module_& m) {
    bind_fit_result(m);
    bind_fit(m);
    bind_render_fit(m);
}

}  // namespace tirpol::python
