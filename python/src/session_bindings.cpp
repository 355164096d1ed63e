// tirpol.calibration, part 2: radiometric calibration (from arrays or a session), temperature from
// counts, polarimetric calibration and reduction of a capture session to Stokes with uncertainties.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "image_conversion.h"
#include "interruptible.h"
#include "python_config.h"
#include "tirpol/calibration/calibration_chain.h"
#include "tirpol/calibration/synthetic_session.h"
#include "tirpol/core/error.h"

namespace py = pybind11;

namespace tirpol::python {

namespace {

using namespace tirpol::calibration;

std::optional<double> optional_fpa(const py::object& fpa_temperature_k) {
    if (fpa_temperature_k.is_none()) return std::nullopt;
    return fpa_temperature_k.cast<double>();
}

/// Counts (H, W) of the calibration's size as a plane; tirpol::Error naming the shapes otherwise.
std::vector<float> counts_plane(const RadiometricCalibration& cal, const py::handle& counts) {
    int width = cal.width, height = cal.height;
    return plane_from_array(counts, "counts", width, height);
}

void bind_radiometric(py::module_& m) {
    py::class_<RadiometricCalibration>(
        m, "RadiometricCalibration",
        "Per-pixel counts → band radiance model (calibration/radiometric.h) with its "
        "bad-pixel map; planes are (H, W) float32.")
        .def_readonly("width", &RadiometricCalibration::width)
        .def_readonly("height", &RadiometricCalibration::height)
        .def_readonly("camera_id", &RadiometricCalibration::camera_id)
        .def_readonly("temperatures_k", &RadiometricCalibration::temperatures_k)
        .def_readonly("warnings", &RadiometricCalibration::warnings)
        .def_property_readonly("band", &RadiometricCalibration::band)
        .def_property_readonly(
            "gain",
            [](const RadiometricCalibration& c) {
                return array_from_plane(std::vector(c.gain), c.width, c.height);
            },
            "counts per W/(m²·sr)")
        .def_property_readonly(
            "offset",
            [](const RadiometricCalibration& c) {
                return array_from_plane(std::vector(c.offset), c.width, c.height);
            },
            "counts")
        .def_property_readonly(
            "bad",
            [](const RadiometricCalibration& c) {
                return array_from_plane(std::vector(c.bad), c.width, c.height);
            },
            "BadPixel bit mask (1 dead, 2 hot, 4 noisy, ...; docs/calibration.md) as float")
        .def("bad_count", [](const RadiometricCalibration& c) { return c.bad_count(); })
        .def(
            "counts_to_radiance",
            [](const RadiometricCalibration& c, const py::object& counts,
               const py::object& fpa_temperature_k) {
                auto plane = counts_plane(c, counts);
                return array_from_plane(
                    counts_to_radiance(c, plane, optional_fpa(fpa_temperature_k)), c.width,
                    c.height);
            },
            py::arg("counts"), py::arg("fpa_temperature_k") = py::none(),
            "Apparent band radiance W/(m²·sr) of a counts image (H, W); bad pixels replaced.")
        .def(
            "temperature_from_counts",
            [](const RadiometricCalibration& c, const py::object& counts,
               const py::object& fpa_temperature_k) {
                auto plane = counts_plane(c, counts);
                const auto radiance = counts_to_radiance(c, plane, optional_fpa(fpa_temperature_k));
                return array_from_plane(brightness_temperature(c.band(), radiance), c.width,
                                        c.height);
            },
            py::arg("counts"), py::arg("fpa_temperature_k") = py::none(),
            "Brightness temperature (K) of a counts image (H, W): counts → radiance → inverse band "
            "Planck; NaN "
            "where the radiance is ≤ 0.")
        .def(
            "write",
            [](const RadiometricCalibration& c, const std::string& path) {
                write_radiometric_calibration(path, c);
            },
            py::arg("path"),
            "Writes the calibration EXR (the file `tirpol calibrate radiometric` writes).");
    m.def("read_radiometric_calibration", &read_radiometric_calibration, py::arg("path"));
    m.def(
        "fit_radiometric",
        [](const py::dict& frames, const Band& band, const py::object& stds, int frames_averaged,
           bool quadratic) {
            int width = 0, height = 0;
            std::vector<BlackbodyFrame> bb;
            for (const auto& [key, value] : frames) {
                BlackbodyFrame f;
                f.temperature_k = key.cast<double>();
                f.source = fmt::format("frames[{} K]", f.temperature_k);
                f.counts = plane_from_array(value, f.source, width, height);
                if (!stds.is_none())
                    f.counts_std = plane_from_array(stds.cast<py::dict>()[key], f.source + " std",
                                                    width, height);
                f.frames = frames_averaged;
                bb.push_back(std::move(f));
            }
            RadiometricOptions options;
            options.quadratic = quadratic;
            py::gil_scoped_release release;
            return fit_radiometric(bb, width, height, band, options);
        },
        py::arg("frames"), py::arg("band"), py::arg("stds") = py::none(),
        py::arg("frames_averaged") = 1, py::arg("quadratic") = false,
        "Per-pixel fit counts = offset + gain·L(T) (+ q·L² when quadratic) to blackbody frames "
        "{temperature_k: counts "
        "(H, W)} (mean of `frames_averaged` frames, σ images `stds` optional), with bad-pixel "
        "detection.");
    m.def(
        "calibrate_radiometric_session",
        [](const std::filesystem::path& dir, const Band& band, bool quadratic) {
            RadiometricOptions options;
            options.quadratic = quadratic;
            py::gil_scoped_release release;
            return calibrate_radiometric_session(dir, band, options);
        },
        py::arg("session_dir"), py::arg("band"), py::arg("quadratic") = false,
        "Radiometric calibration from a session's blackbody records (docs/session-format.md).");
}

void bind_session(py::module_& m) {
    py::class_<PolarimetricCalibration>(
        m, "PolarimetricCalibration", "Analyzer model and wire-grid τ/B maps from a field session.")
        .def_readonly("analyzer", &PolarimetricCalibration::analyzer)
        .def_readonly("analyzer_method", &PolarimetricCalibration::analyzer_method)
        .def_readonly("wire_grid", &PolarimetricCalibration::wire_grid)
        .def_readonly("session", &PolarimetricCalibration::session);
    m.def(
        "calibrate_polarimetric_session",
        [](const std::filesystem::path& dir, const RadiometricCalibration& radiometric) {
            py::gil_scoped_release release;
            return calibrate_polarimetric_session(dir, radiometric);
        },
        py::arg("session_dir"), py::arg("radiometric"),
        "Polarimetric calibration: wire-grid τ/B maps from the blackbody records through the "
        "polarizer, the "
        "analyzer by least squares from the known-source repeats (ideal when there are none).");
    m.def(
        "reduce_session",
        [](const std::filesystem::path& dir, const RadiometricCalibration& radiometric,
           const PolarimetricCalibration* polarimetric, bool update_offset, bool include_slar,
           bool force_other_camera) {
            SessionReductionOptions options;
            options.update_offset = update_offset;
            options.include_slar = include_slar;
            options.force_other_camera = force_other_camera;
            Image result = run_interruptible([&](const std::atomic<bool>& cancel) {
                SessionReductionOptions o = options;
                o.cancel = &cancel;
                return reduce_session(dir, radiometric, polarimetric, o);
            });
            return to_python(std::move(result));
        },
        py::arg("session_dir"), py::arg("radiometric"), py::arg("polarimetric") = py::none(),
        py::arg("update_offset") = false, py::arg("include_slar") = false,
        py::arg("force_other_camera") = false,
        "Reduces a session's scene records to Stokes in radiance units: S0 S1 S2 DoLP AoP and "
        "their *_std, "
        "repeats averaged, bad pixels replaced, wire grid removed with `polarimetric`. Releases "
        "the GIL; Ctrl-C "
        "stops it (KeyboardInterrupt).");
    m.def(
        "write_synthetic_sessions",
        [](const std::filesystem::path& root, const Band& band, int width, int height) {
            SyntheticCamera camera;
            camera.width = width;
            camera.height = height;
            Image truth = synthetic_panel_scene(width, height, band);
            {
                py::gil_scoped_release release;
                write_synthetic_sessions(root, camera, truth, band);
            }
            return to_python(std::move(truth));
        },
        py::arg("root"), py::arg("band"), py::arg("width") = 64, py::arg("height") = 48,
        "Writes the synthetic sessions lab/ (blackbody, no polarizer), polcal/ (blackbody through "
        "the polarizer "
        "and a known source) and scene/ (a 300 K panel with ε_S0 = 0.93, ε_S1 = −0.035 in front of "
        "a 280 K "
        "background, an IR reflector at the left) of a simulated uncooled camera "
        "(calibration/synthetic_session.h); "
        "returns the true scene Stokes image S0 S1 S2.");
}

PixelRect rect_of(const py::handle& rect, const std::string& what) {
    const auto v = rect.cast<std::vector<int>>();
    if (v.size() != 4)
        fail("{}: expected a rectangle [x, y, width, height], got {} numbers", what, v.size());
    return {v[0], v[1], v[2], v[3]};
}

py::dict result_dict(const EmissivityResult& r) {
    py::dict d;
    d["name"] = r.name;
    d["view_angle_deg"] = r.view_angle_deg;
    d["temperature_k"] = r.temperature_k;
    d["pixels"] = r.pixels;
    d["l_dw_w_m2_sr"] = r.l_dw_w_m2_sr;
    d["l_bb_w_m2_sr"] = r.l_bb_w_m2_sr;
    d["eps_s0"] = r.eps_s0;
    d["eps_s0_std"] = r.eps_s0_std;
    d["eps_s1"] = r.eps_s1;
    d["eps_s1_std"] = r.eps_s1_std;
    d["eps_s2"] = r.eps_s2;
    d["eps_s2_std"] = r.eps_s2_std;
    d["warnings"] = r.warnings;
    return d;
}

/// The reflector as [x, y, w, h], or as the ROI file's mapping {rect, emissivity, emissivity_std,
/// temperature_k, temperature_std_k}, read by the ROI file's own parser.
EmissivityReflector reflector_from_python(const py::object& reflector) {
    if (!py::isinstance<py::dict>(reflector)) return {rect_of(reflector, "reflector")};
    return EmissivityReflector::from_config(config_from_python(reflector, "<reflector dict>"));
}

/// The regions of eq 17 from Python: the IR reflector and the targets' dicts.
EmissivityRois rois_from_python(const py::object& reflector, const py::list& targets) {
    EmissivityRois rois;
    rois.reflector = reflector_from_python(reflector);
    for (const auto& t : targets) {
        const auto d = t.cast<py::dict>();
        EmissivityTarget target;
        target.name = d["name"].cast<std::string>();
        target.rect = rect_of(d["rect"], "targets['" + target.name + "'].rect");
        target.view_angle_deg = d["view_angle_deg"].cast<double>();
        if (d.contains("temperature_k")) target.temperature_k = d["temperature_k"].cast<double>();
        if (d.contains("temperature_std_k"))
            target.temperature_std_k = d["temperature_std_k"].cast<double>();
        if (d.contains("blackbody_rect"))
            target.blackbody_rect =
                rect_of(d["blackbody_rect"], "targets['" + target.name + "'].blackbody_rect");
        rois.targets.push_back(std::move(target));
    }
    return rois;
}

void bind_emissivity(py::module_& m) {
    m.def(
        "extract_emissivity",
        [](const py::object& stokes, const py::object& reflector, const py::list& targets,
           const Band& band) {
            const EmissivityRois rois = rois_from_python(reflector, targets);
            const Image image = image_from_python(stokes);
            py::list out;
            for (const auto& r : extract_emissivity(image, rois, band)) out.append(result_dict(r));
            return out;
        },
        py::arg("stokes"), py::arg("reflector"), py::arg("targets"), py::arg("band"),
        "Polarized emissivity of targets in a reduced Stokes image (paper eq 17): the IR reflector "
        "rectangle "
        "[x, y, w, h] gives the downwelling radiance (or {rect, emissivity, emissivity_std, "
        "temperature_k, "
        "temperature_std_k}, as in the ROI file, to remove the reflector's own emission), each "
        "target {name, rect, "
        "view_angle_deg, temperature_k "
        "(contact) or blackbody_rect, temperature_std_k} its ε_S0, ε_S1, ε_S2 with 1σ "
        "uncertainties eps_s0_std, "
        "eps_s1_std, eps_s2_std; ε_S1 and ε_S2 in the image Stokes frame (fit_microfacet takes "
        "ε_S1 in the "
        "plane-of-emission frame).");
}

/// The chain's products as a dict; emissivity rows as extract_emissivity returns them.
py::dict products_dict(ChainProducts p) {
    py::dict d;
    d["radiometric"] = p.radiometric ? py::cast(std::move(*p.radiometric)) : py::none();
    d["polarimetric"] = p.polarimetric ? py::cast(std::move(*p.polarimetric)) : py::none();
    py::list stokes, emissivity;
    for (auto& image : p.stokes) stokes.append(to_python(std::move(image)));
    for (const auto& rows : p.emissivity) {
        py::list out;
        for (const auto& r : rows) out.append(result_dict(r));
        emissivity.append(out);
    }
    d["stokes"] = stokes;
    d["emissivity"] = emissivity;
    return d;
}

void bind_chain(py::module_& m) {
    m.def(
        "calibration_steps",
        [] {
            py::list out;
            for (const auto& s : calibration_steps())
                out.append(py::dict(py::arg("name") = std::string(s.name),
                                    py::arg("needs") = std::string(s.needs),
                                    py::arg("makes") = std::string(s.makes)));
            return out;
        },
        "The steps of the calibration chain in the order run_chain runs them: [{name, needs, "
        "makes}].");
    m.def(
        "run_chain",
        [](const Band& band, const std::vector<std::filesystem::path>& blackbody_sessions,
           const std::optional<std::filesystem::path>& polarimetric_session,
           const std::vector<std::filesystem::path>& scene_sessions, const py::sequence& regions,
           const std::optional<RadiometricCalibration>& radiometric,
           const std::optional<PolarimetricCalibration>& polarimetric, bool update_offset) {
            ChainInputs in;
            in.band = band;
            in.blackbody_sessions = blackbody_sessions;
            if (polarimetric_session) in.polarimetric_session = *polarimetric_session;
            in.scene_sessions = scene_sessions;
            in.reduction.update_offset = update_offset;
            for (const auto& r : regions) {
                const auto d = r.cast<py::dict>();
                in.rois.push_back(rois_from_python(d["reflector"], d["targets"].cast<py::list>()));
            }
            ChainProducts given;
            given.radiometric = radiometric;
            given.polarimetric = polarimetric;
            return products_dict(run_interruptible([&](const std::atomic<bool>& cancel) {
                ChainInputs with_cancel = in;
                with_cancel.reduction.cancel = &cancel;
                return run_calibration_chain(with_cancel, given);
            }));
        },
        py::arg("band"), py::arg("blackbody_sessions") = std::vector<std::filesystem::path>{},
        py::arg("polarimetric_session") = py::none(),
        py::arg("scene_sessions") = std::vector<std::filesystem::path>{},
        py::arg("regions") = py::list(), py::arg("radiometric") = py::none(),
        py::arg("polarimetric") = py::none(), py::arg("update_offset") = false,
        "Runs the calibration chain (calibration_steps(), the order the CLI, the demo and the "
        "digital twin use): "
        "radiometric calibration from `blackbody_sessions`, polarimetric calibration from "
        "`polarimetric_session`, "
        "one Stokes image per `scene_sessions` entry, and ε per target (eq 17) for `regions` — one "
        "{reflector, targets} dict (extract_emissivity's arguments) for every image, or one per "
        "image. A step runs "
        "when its inputs are given; `radiometric`/`polarimetric` given (e.g. read from files) skip "
        "their steps. "
        "Returns {radiometric, polarimetric, stokes: [Image], emissivity: [[row]]}. Releases the "
        "GIL; Ctrl-C "
        "stops the reduction (KeyboardInterrupt).");
}

}  // namespace

void bind_calibration_sessions(py::module_& m) {
    bind_radiometric(m);
    bind_session(m);
    bind_emissivity(m);
    bind_chain(m);
}

}  // namespace tirpol::python
