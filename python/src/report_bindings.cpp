// tirpol.report: the measured-vs-simulated comparison. compare() computes (statistics as a dict
// with the keys of report.json, docs/report.md); Comparison.write_html() presents.
#include <fmt/format.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>

#include "bindings.h"
#include "image_conversion.h"
#include "interruptible.h"
#include "python_config.h"
#include "tirpol/core/camera_model.h"
#include "tirpol/core/error.h"
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

bool is_path(const py::handle& object) {
    return py::isinstance<py::str>(object) ||
           py::isinstance(object, py::module_::import("os").attr("PathLike"));
}

std::string python_repr(const py::handle& object) { return py::repr(object).cast<std::string>(); }

/// `points` as an (n, columns) list of finite floats, else ValueError naming `what`.
py::list finite_rows(const py::handle& points, std::size_t columns, const std::string& what,
                     const std::string& expected) {
    const py::module_ np = py::module_::import("numpy");
    py::object array;
    try {
        array = np.attr("asarray")(points, py::arg("dtype") = np.attr("float64"));
    } catch (const py::error_already_set&) {
        throw py::value_error(
            fmt::format("{}: expected {}, got {}", what, expected, python_repr(points)));
    }
    const auto shape = array.attr("shape").cast<std::vector<std::size_t>>();
    if (shape.size() != 2 || shape[1] != columns)
        throw py::value_error(fmt::format("{}: expected {}, got an array of shape {}", what,
                                          expected, python_repr(array.attr("shape"))));
    if (!np.attr("all")(np.attr("isfinite")(array)).cast<bool>())
        throw py::value_error(fmt::format("{}: expected finite pixel coordinates, got {}", what,
                                          python_repr(points)));
    return array.attr("tolist")();
}

/// Regions as Python gives them: a regions YAML path; the YAML's structure as a dict
/// ({"regions": [{"name", "polygon"}], "background", "noise_region"}); a dict name → polygon; or a
/// list of {"name", "polygon"}. Polygons are (n, 2) array-likes of measured pixels [x, y]. Checked
/// by the regions file's own parser, so the messages are the same.
report::RegionSet regions_from_python(const py::handle& regions,
                                      const std::optional<std::string>& background,
                                      const std::optional<std::string>& noise_region) {
    if (is_path(regions)) {
        if (background || noise_region)
            throw py::value_error(
                "background, noise_region: name them in the regions file when regions is a path");
        return report::load_regions(regions.cast<std::filesystem::path>());
    }
    py::dict set;
    py::list list;
    auto add = [&](const py::handle& name, const py::handle& polygon, const std::string& where) {
        if (!py::isinstance<py::str>(name))
            throw py::value_error(
                fmt::format("{}: expected a region name (str), got {}", where, python_repr(name)));
        py::dict region;
        region["name"] = name;
        region["polygon"] = finite_rows(polygon, 2, where + " polygon",
                                        "an (n, 2) array of pixel coordinates [x, y], n ≥ 3");
        list.append(region);
    };
    if (py::isinstance<py::dict>(regions) && regions.cast<py::dict>().contains("regions")) {
        // The regions file's structure.
        const py::dict given = regions.cast<py::dict>();
        for (const auto& [key, value] : given) {
            const std::string k = py::str(key).cast<std::string>();
            if (k != "regions" && k != "background" && k != "noise_region")
                throw py::value_error(fmt::format(
                    "regions: unknown key '{}'; expected 'regions', 'background', 'noise_region'",
                    k));
        }
        auto name_of = [&](const char* key, const std::optional<std::string>& argument) {
            if (!given.contains(key)) return argument;
            if (argument)
                throw py::value_error(
                    fmt::format("{}: given both in regions and as an argument", key));
            if (!py::isinstance<py::str>(given[key]))
                throw py::value_error(
                    fmt::format("regions['{}']: expected a region name (str), "
                                "got {}",
                                key, python_repr(given[key])));
            return std::optional<std::string>(given[key].cast<std::string>());
        };
        return regions_from_python(given["regions"], name_of("background", background),
                                   name_of("noise_region", noise_region));
    }
    if (py::isinstance<py::dict>(regions)) {
        for (const auto& [name, polygon] : regions.cast<py::dict>())
            add(name, polygon, fmt::format("regions[{}]", python_repr(name)));
    } else if (py::isinstance<py::sequence>(regions) && !py::isinstance<py::str>(regions)) {
        std::size_t i = 0;
        for (const auto& item : regions.cast<py::sequence>()) {
            const std::string where = fmt::format("regions[{}]", i++);
            if (!py::isinstance<py::dict>(item) || !item.cast<py::dict>().contains("name") ||
                !item.cast<py::dict>().contains("polygon") || py::len(item) != 2)
                throw py::value_error(
                    fmt::format("{}: expected a dict with 'name' and 'polygon', got {}", where,
                                python_repr(item)));
            add(item["name"], item["polygon"], where);
        }
    } else {
        throw py::value_error(fmt::format(
            "regions: expected a regions YAML path, a dict name → polygon, or a list of dicts "
            "with 'name' and 'polygon', got {}",
            python_repr(regions)));
    }
    set["regions"] = list;
    if (background) set["background"] = *background;
    if (noise_region) set["noise_region"] = *noise_region;
    return report::parse_regions(config_from_python(set, "regions"));
}

/// Control points: a YAML path (tirpol compare --control-points), an (n, 4) array of rows
/// [measured x, measured y, simulated x, simulated y], or a pair (measured (n, 2), simulated (n,
/// 2)).
std::vector<report::TiePoint> control_points_from_python(const py::handle& points) {
    if (is_path(points)) return report::load_control_points(points.cast<std::filesystem::path>());
    const std::string expected =
        "an (n, 4) array of [measured x, measured y, simulated x, simulated y], or a pair of "
        "(n, 2) arrays (measured, simulated), n ≥ 4";
    std::vector<report::TiePoint> out;
    if (py::isinstance<py::tuple>(points) && py::len(points) == 2) {
        const auto pair = points.cast<py::tuple>();
        const py::list measured = finite_rows(pair[0], 2, "control_points[0] (measured)", expected);
        const py::list simulated =
            finite_rows(pair[1], 2, "control_points[1] (simulated)", expected);
        if (py::len(measured) != py::len(simulated))
            throw py::value_error(fmt::format(
                "control_points: {} measured points but {} simulated ones; expected pairs",
                py::len(measured), py::len(simulated)));
        for (std::size_t i = 0; i < py::len(measured); ++i) {
            const auto m = measured[i].cast<std::vector<double>>();
            const auto s = simulated[i].cast<std::vector<double>>();
            out.push_back({{m[0], m[1]}, {s[0], s[1]}});
        }
    } else {
        for (const auto& row : finite_rows(points, 4, "control_points", expected)) {
            const auto r = row.cast<std::vector<double>>();
            out.push_back({{r[0], r[1]}, {r[2], r[3]}});
        }
    }
    if (out.size() < 4)
        throw py::value_error(
            fmt::format("control_points: a homography needs at least 4 pairs, got {}", out.size()));
    return out;
}

/// The CLI's default: the camera model when given, else control points when given, else automatic;
/// a method that needs one of them checked for it.
report::RegistrationMethod registration_method(const std::optional<std::string>& requested,
                                               const CompareOptions& o) {
    if (!requested)
        return o.camera_model              ? report::RegistrationMethod::CameraModel
               : !o.control_points.empty() ? report::RegistrationMethod::ControlPoints
                                           : report::RegistrationMethod::Auto;
    report::RegistrationMethod method;
    try {
        method = report::parse_registration_method(*requested);
    } catch (const Error& e) {
        throw py::value_error(std::string("registration: ") + e.what());
    }
    if (method == report::RegistrationMethod::ControlPoints && o.control_points.empty())
        throw py::value_error("registration: 'control-points' needs control_points");
    if (method == report::RegistrationMethod::CameraModel && !o.camera_model)
        throw py::value_error("registration: 'camera-model' needs camera_model");
    if (o.camera_model && method != report::RegistrationMethod::CameraModel)
        throw py::value_error(fmt::format(
            "registration: a camera model registers by the model; leave registration out or give "
            "'camera-model', not '{}'",
            *requested));
    return method;
}

/// A number argument in the range the CLI accepts, else ValueError naming it.
double checked(double value, bool ok, const char* argument, const char* expected) {
    if (!ok)
        throw py::value_error(fmt::format("{}: expected {}, got {}", argument, expected, value));
    return value;
}

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
        [](const py::object& measured, const py::object& simulated,
           const std::optional<std::string>& registration, const py::object& regions,
           const std::optional<std::string>& background,
           const std::optional<std::string>& noise_region, const py::object& control_points,
           const std::optional<std::filesystem::path>& camera_model,
           std::optional<double> measured_frame_sigma, double gain_sigma, double offset_sigma,
           double false_alarm, double power, std::optional<std::array<double, 2>> band_um,
           const std::string& measured_name, const std::string& simulated_name) {
            PyComparison c;
            CompareOptions& o = c.options;
            if (!regions.is_none()) {
                o.regions = regions_from_python(regions, background, noise_region);
                if (is_path(regions))
                    o.provenance.inputs.push_back(
                        report::describe_input("regions", regions.cast<std::filesystem::path>()));
            } else if (background || noise_region) {
                throw py::value_error("background, noise_region: they name regions; give regions");
            }
            if (!control_points.is_none()) {
                o.control_points = control_points_from_python(control_points);
                if (is_path(control_points))
                    o.provenance.inputs.push_back(report::describe_input(
                        "control points", control_points.cast<std::filesystem::path>()));
            }
            if (camera_model) {
                o.camera_model = read_camera_model(*camera_model);
                o.camera_model_name = camera_model->string();
                o.provenance.inputs.push_back(
                    report::describe_input("camera model", *camera_model));
            }
            o.registration = registration_method(registration, o);
            if (measured_frame_sigma)
                o.measured_frame_sigma =
                    checked(*measured_frame_sigma,
                            *measured_frame_sigma > 0.0 && std::isfinite(*measured_frame_sigma),
                            "measured_frame_sigma", "a positive radiance in W/(m²·sr)");
            o.measured_gain_sigma_relative =
                checked(gain_sigma, gain_sigma >= 0.0 && gain_sigma < 1.0, "gain_sigma",
                        "a relative gain uncertainty in [0, 1)");
            o.measured_offset_sigma =
                checked(offset_sigma, offset_sigma >= 0.0 && std::isfinite(offset_sigma),
                        "offset_sigma", "a non-negative radiance in W/(m²·sr)");
            o.design.false_alarm_per_region =
                checked(false_alarm, false_alarm > 0.0 && false_alarm < 0.5, "false_alarm",
                        "a probability in (0, 0.5)");
            o.design.power =
                checked(power, power > 0.5 && power < 1.0, "power", "a probability in (0.5, 1)");
            if (band_um && !((*band_um)[0] > 0.0 && (*band_um)[1] > (*band_um)[0] &&
                             std::isfinite((*band_um)[1])))
                throw py::value_error(
                    fmt::format("band_um: expected (lo, hi) in µm with 0 < lo < hi, got ({}, {})",
                                (*band_um)[0], (*band_um)[1]));
            o.band_um = band_um;
            o.measured_name = measured_name;
            o.simulated_name = simulated_name;
            const Image m_image = image_from_python(measured);
            const Image s_image = image_from_python(simulated);
            c.comparison = run_interruptible([&](const std::atomic<bool>& cancel) {
                report::CompareOptions with_cancel = o;
                with_cancel.cancel = &cancel;
                return report::compare(m_image, s_image, with_cancel);
            });
            return c;
        },
        py::arg("measured"), py::arg("simulated"), py::arg("registration") = py::none(),
        py::arg("regions") = py::none(), py::arg("background") = py::none(),
        py::arg("noise_region") = py::none(), py::arg("control_points") = py::none(),
        py::arg("camera_model") = py::none(), py::arg("measured_frame_sigma") = py::none(),
        py::arg("gain_sigma") = 0.0, py::arg("offset_sigma") = 0.0, py::arg("false_alarm") = 0.05,
        py::arg("power") = 0.80, py::arg("band_um") = py::none(),
        py::arg("measured_name") = "measured", py::arg("simulated_name") = "simulated",
        "Compares a measured Stokes image with a simulated one (tirpol.Image or dicts with S0 S1 "
        "S2 and, for z statistics, S*_std / S*_var), as `tirpol compare` does: registration "
        "(None: 'camera-model' with camera_model, 'control-points' with control_points, else "
        "'auto' (ECC on S0 gradients); 'none': identity, same size), per-region statistics, z "
        "maps and verdicts. regions: a regions YAML path, a dict name → polygon, or a list of "
        "{'name', 'polygon'} (polygons: (n, 2) arrays of measured pixels [x, y]), with optional "
        "background and noise_region names. control_points: a YAML path, an (n, 4) array "
        "[mx, my, sx, sy] or a pair of (n, 2) arrays. camera_model: the measured camera's "
        "camera.yaml (tirpol calibrate geometric). gain_sigma, offset_sigma, false_alarm, power: "
        "as --gain-sigma, --offset-sigma, --false-alarm, --power (docs/report.md). Writes "
        "nothing; see Comparison.statistics and Comparison.write_html. Releases the GIL; Ctrl-C "
        "stops it between its stages (KeyboardInterrupt).");
}

}  // namespace tirpol::python
