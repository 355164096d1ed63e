// tirpol.fitting.fit_through_renderer: micro-facet parameters fitted through the renderer to
// measured Stokes images given as tirpol.Image (or dicts of arrays), returning a dict.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "image_conversion.h"
#include "interruptible.h"
#include "python_config.h"
#include "tirpol/core/error.h"
#include "tirpol/fitting/render_fit.h"

namespace py = pybind11;

namespace tirpol::python {

namespace {

using namespace tirpol::fitting;

RenderFitView view_of(const simulation::Scene& scene, const py::dict& d, std::size_t index) {
    const std::string where = fmt::format("views[{}]", index);
    for (const auto& [key, value] : d) {
        const auto k = key.cast<std::string>();
        if (k != "measured" && k != "camera" && k != "regions" && k != "objects" && k != "name")
            fail("{}: unknown key '{}' (expected measured, camera, regions, objects, name)", where,
                 k);
    }
    if (!d.contains("measured"))
        fail("{}: no 'measured' image (S0 S1 S2 S0_std S1_std S2_std)", where);
    Image measured = image_from_python(d["measured"]);
    const simulation::PinholeCamera camera =
        d.contains("camera")
            ? simulation::PinholeCamera::from_config(config_from_python(
                  d["camera"], std::filesystem::path(fmt::format("<{}.camera>", where))))
            : scene.camera.resized(measured.width(), measured.height());
    RenderFitView v{d.contains("name") ? d["name"].cast<std::string>() : where,
                    camera,
                    std::move(measured),
                    {}};
    if (d.contains("objects"))
        v.regions = object_regions(scene, v.camera, d["objects"].cast<std::vector<std::string>>());
    if (d.contains("regions"))
        for (const auto& [name, mask_object] : d["regions"].cast<py::dict>()) {
            const auto mask =
                mask_object.cast<py::array_t<bool, py::array::c_style | py::array::forcecast>>();
            if (mask.ndim() != 2 || mask.shape(0) != v.measured.height() ||
                mask.shape(1) != v.measured.width())
                fail("{}: regions['{}']: expected a boolean mask of shape ({}, {})", where,
                     name.cast<std::string>(), v.measured.height(), v.measured.width());
            RenderFitRegion r{name.cast<std::string>(), {}};
            for (py::ssize_t i = 0; i < mask.size(); ++i)
                if (mask.data()[i]) r.pixels.push_back(static_cast<std::size_t>(i));
            v.regions.push_back(std::move(r));
        }
    if (v.regions.empty()) fail("{}: no 'regions' masks and no 'objects' to compare", where);
    return v;
}

RenderFitParameter parameter_of(const py::dict& d, std::size_t index) {
    const std::string where = fmt::format("parameters[{}]", index);
    for (const char* key : {"material", "name", "lower", "upper"})
        if (!d.contains(key))
            fail("{}: no '{}' (expected material, name, lower, upper[, initial, step])", where,
                 key);
    RenderFitParameter p;
    p.material = d["material"].cast<std::string>();
    p.parameter = parameter_from_name(d["name"].cast<std::string>());
    p.lower = d["lower"].cast<double>();
    p.upper = d["upper"].cast<double>();
    if (d.contains("initial")) p.initial = d["initial"].cast<double>();
    if (d.contains("step")) p.step = d["step"].cast<double>();
    return p;
}

py::dict summary_dict(const RenderFitSummary& s) {
    py::list parameters;
    for (const auto& p : s.parameters)
        parameters.append(py::dict(py::arg("material") = p.material, py::arg("name") = p.name,
                                   py::arg("value") = p.value, py::arg("sigma") = p.std_uncertainty,
                                   py::arg("initial") = p.initial, py::arg("lower") = p.lower,
                                   py::arg("upper") = p.upper, py::arg("step") = p.step));
    return py::dict(py::arg("parameters") = parameters, py::arg("covariance") = s.covariance,
                    py::arg("correlation") = s.correlation,
                    py::arg("covariance_available") = s.covariance_available,
                    py::arg("chi2") = s.chi2, py::arg("dof") = s.dof,
                    py::arg("reduced_chi2") = s.reduced_chi2, py::arg("usable") = s.usable,
                    py::arg("termination") = s.termination.text(), py::arg("renders") = s.renders,
                    py::arg("iterations") = s.iterations, py::arg("seconds") = s.seconds,
                    py::arg("warnings") = s.warnings, py::arg("report") = s.FullReport());
}

}  // namespace

void bind_render_fit(py::module_& m) {
    m.def(
        "fit_through_renderer",
        [](const simulation::Scene& scene, const py::list& views, const py::list& parameters,
           const std::vector<int>& stokes, bool pixels, int samples_per_pixel,
           std::optional<std::uint64_t> seed, bool forward, int max_iterations, int threads) {
            RenderFitOptions o;
            for (const auto& p : parameters)
                o.parameters.push_back(parameter_of(p.cast<py::dict>(), o.parameters.size()));
            std::vector<RenderFitView> vs;
            for (const auto& v : views) vs.push_back(view_of(scene, v.cast<py::dict>(), vs.size()));
            o.stokes = stokes;
            o.residuals = pixels ? RenderFitResiduals::pixels : RenderFitResiduals::region_means;
            o.samples_per_pixel = samples_per_pixel;
            o.seed = seed;
            o.differences = forward ? FiniteDifference::forward : FiniteDifference::central;
            o.max_iterations = max_iterations;
            o.threads = threads;
            const RenderFitSummary s = run_interruptible([&](const std::atomic<bool>& cancel) {
                RenderFitOptions with_cancel = o;
                with_cancel.cancel = &cancel;
                return fit_through_renderer(scene, vs, with_cancel);
            });
            return summary_dict(s);
        },
        py::arg("scene"), py::arg("views"), py::arg("parameters"),
        py::arg("stokes") = std::vector<int>{0, 1, 2}, py::arg("pixels") = false,
        py::arg("samples_per_pixel") = 0, py::arg("seed") = py::none(), py::arg("forward") = false,
        py::arg("max_iterations") = 20, py::arg("threads") = 0,
        "Fits micro-facet parameters of the scene's materials through the renderer "
        "(docs/fitting.md): every "
        "evaluation renders each view with the same seed and compares region means (or pixels) of "
        "S0, S1, S2 with "
        "the measured ones, weighted by 1/(σ_meas² + σ_render²). views: list of dicts {'measured': "
        "tirpol.Image or "
        "dict with S0 S1 S2 S0_std S1_std S2_std, 'camera': optional scene-file camera mapping "
        "(default: the "
        "scene's, resized), 'regions': {name: bool mask (H, W)} and/or 'objects': [scene object "
        "names], 'name'}. "
        "parameters: list of dicts {'material', 'name' ('n', 'sigma', …), 'lower', 'upper', "
        "optional 'initial', "
        "'step'}. Returns a dict: parameters (value, sigma, …), covariance, correlation, chi2, "
        "dof, reduced_chi2, "
        "usable, termination, renders, iterations, seconds, warnings, report (text). Releases the "
        "GIL; Ctrl-C "
        "stops it (KeyboardInterrupt).");
}

}  // namespace tirpol::python
