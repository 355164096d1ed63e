// tirpol.report: the measured-vs-simulated comparison. compare() computes (statistics as a dict
// with the keys of report.json, docs/report.md); Comparison.write_html() presents.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "image_conversion.h"
#include "interruptible.h"
#include "tirpol/report/comparison_report.h"

namespace py = pybind11;

namespace tirpol::python {

namespace {

using report::CompareOptions;
using report::Comparison;

/// A comparison and the options it was made with (write_report needs both).
struct PyComparison {
    Comparison comparison;
    CompareOptions options;

    py::object statistics() const {
        return py::module_::import("json").attr("loads")(
            report::comparison_json(comparison.result));
    }
};

}  // namespace

void bind_report(py::module_& m) {
    py::class_<PyComparison>(m, "Comparison",
                             "A measured-vs-simulated comparison (report/comparison_report.h).")
        .def_property_readonly(
            "statistics", &PyComparison::statistics,
            "Every number of the comparison as a dict: the content of report.json (keys in "
            "docs/report.md): registration, noise sources, per-region statistics, z and verdicts.")
        .def(
            "write_html",
            [](PyComparison& c, const std::filesystem::path& report_dir) {
                {
                    py::gil_scoped_release release;
                    report::write_report(c.comparison, c.options, report_dir);
                }
                return c.comparison.result.html;
            },
            py::arg("report_dir"),
            "Writes report.html, report.json, comparison.exr and the figures into report_dir; "
            "returns the HTML path.");
    m.def(
        "compare",
        [](const py::object& measured, const py::object& simulated, const std::string& registration,
           std::optional<double> measured_frame_sigma, std::optional<std::array<double, 2>> band_um,
           const std::string& measured_name, const std::string& simulated_name) {
            const Image m_image = image_from_python(measured);
            const Image s_image = image_from_python(simulated);
            PyComparison c;
            c.options.registration = report::parse_registration_method(registration);
            c.options.measured_frame_sigma = measured_frame_sigma;
            c.options.band_um = band_um;
            c.options.measured_name = measured_name;
            c.options.simulated_name = simulated_name;
            c.comparison = run_interruptible([&](const std::atomic<bool>& cancel) {
                report::CompareOptions o = c.options;
                o.cancel = &cancel;
                return report::compare(m_image, s_image, o);
            });
            return c;
        },
        py::arg("measured"), py::arg("simulated"), py::arg("registration") = "auto",
        py::arg("measured_frame_sigma") = py::none(), py::arg("band_um") = py::none(),
        py::arg("measured_name") = "measured", py::arg("simulated_name") = "simulated",
        "Compares a measured Stokes image with a simulated one (tirpol.Image or dicts with S0 S1 "
        "S2 and, for "
        "z statistics, S*_std / S*_var): registration ('auto': ECC on S0 gradients; 'none': "
        "identity, same size), "
        "per-region statistics, z maps and verdicts. Writes "
        "nothing; see Comparison.statistics and Comparison.write_html. Releases the GIL; Ctrl-C "
        "stops it between "
        "its stages (KeyboardInterrupt).");
}

}  // namespace tirpol::python
