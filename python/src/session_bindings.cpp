// tirpol.calibration, part 2: radiometric calibration (from arrays or a session), temperature from
// counts, polarimetric calibration and reduction of a capture session to Stokes with uncertainties.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "image_conversion.h"
#include "tirpol/calibration/emissivity_extraction.h"
#include "tirpol/calibration/noise.h"
#include "tirpol/calibration/session_calibration.h"
#include "tirpol/calibration/testing/synthetic_session.h"
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
    py::class_<RadiometricCalibration>(m, "RadiometricCalibration",
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
            [](const RadiometricCalibration& c) { return array_from_plane(std::vector(c.gain), c.width, c.height); },
            "counts per W/(m²·sr)")
        .def_property_readonly(
            "offset",
            [](const RadiometricCalibration& c) { return array_from_plane(std::vector(c.offset), c.width, c.height); },
            "counts")
        .def_property_readonly(
            "bad",
            [](const RadiometricCalibration& c) { return array_from_plane(std::vector(c.bad), c.width, c.height); },
            "BadPixel bit mask (1 dead, 2 hot, 4 noisy, ...; docs/calibration.md) as float")
        .def("bad_count", [](const RadiometricCalibration& c) { return c.bad_count(); })
        .def(
            "counts_to_radiance",
            [](const RadiometricCalibration& c, const py::object& counts, const py::object& fpa_temperature_k) {
                auto plane = counts_plane(c, counts);
                return array_from_plane(counts_to_radiance(c, plane, optional_fpa(fpa_temperature_k)), c.width,
                                        c.height);
            },
            py::arg("counts"), py::arg("fpa_temperature_k") = py::none(),
            "Apparent band radiance W/(m²·sr) of a counts image (H, W); bad pixels replaced.")
        .def(
            "temperature_from_counts",
            [](const RadiometricCalibration& c, const py::object& counts, const py::object& fpa_temperature_k) {
                auto plane = counts_plane(c, counts);
                const auto radiance = counts_to_radiance(c, plane, optional_fpa(fpa_temperature_k));
                return array_from_plane(brightness_temperature(c.band(), radiance), c.width, c.height);
            },
            py::arg("counts"), py::arg("fpa_temperature_k") = py::none(),
            "Brightness temperature (K) of a counts image (H, W): counts → radiance → inverse band Planck; NaN "
            "where the radiance is ≤ 0.")
        .def(
            "write",
            [](const RadiometricCalibration& c, const std::string& path) { write_radiometric_calibration(path, c); },
            py::arg("path"), "Writes the calibration EXR (the file `tirpol calibrate radiometric` writes).");
    m.def("read_radiometric_calibration", &read_radiometric_calibration, py::arg("path"));
    m.def(
        "fit_radiometric",
        [](const py::dict& frames, const Band& band, const py::object& stds, int frames_averaged, bool quadratic) {
            int width = 0, height = 0;
            std::vector<BlackbodyFrame> bb;
            for (const auto& [key, value] : frames) {
                BlackbodyFrame f;
                f.temperature_k = key.cast<double>();
                f.source = fmt::format("frames[{} K]", f.temperature_k);
                f.counts = plane_from_array(value, f.source, width, height);
                if (!stds.is_none())
                    f.counts_std = plane_from_array(stds.cast<py::dict>()[key], f.source + " std", width, height);
                f.frames = frames_averaged;
                bb.push_back(std::move(f));
            }
            RadiometricOptions options;
            options.quadratic = quadratic;
            py::gil_scoped_release release;
            return fit_radiometric(bb, width, height, band, options);
        },
        py::arg("frames"), py::arg("band"), py::arg("stds") = py::none(), py::arg("frames_averaged") = 1,
        py::arg("quadratic") = false,
        "Per-pixel fit counts = offset + gain·L(T) (+ q·L² when quadratic) to blackbody frames {temperature_k: counts "
        "(H, W)} (mean of `frames_averaged` frames, σ images `stds` optional), with bad-pixel detection.");
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
    py::class_<PolarimetricCalibration>(m, "PolarimetricCalibration",
                                        "Analyzer model and wire-grid τ/B maps from a field session.")
        .def_readonly("analyzer", &PolarimetricCalibration::analyzer)
        .def_readonly("analyzer_method", &PolarimetricCalibration::analyzer_method)
        .def_readonly("session", &PolarimetricCalibration::session);
    m.def(
        "calibrate_polarimetric_session",
        [](const std::filesystem::path& dir, const RadiometricCalibration& radiometric) {
            py::gil_scoped_release release;
            return calibrate_polarimetric_session(dir, radiometric);
        },
        py::arg("session_dir"), py::arg("radiometric"),
        "Polarimetric calibration: wire-grid τ/B maps from the blackbody records through the polarizer, the "
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
            Image result;
            {
                py::gil_scoped_release release;
                result = reduce_session(dir, radiometric, polarimetric, options);
            }
            return to_python(std::move(result));
        },
        py::arg("session_dir"), py::arg("radiometric"), py::arg("polarimetric") = py::none(),
        py::arg("update_offset") = false, py::arg("include_slar") = false, py::arg("force_other_camera") = false,
        "Reduces a session's scene records to Stokes in radiance units: S0 S1 S2 DoLP AoP and their *_std, "
        "repeats averaged, bad pixels replaced, wire grid removed with `polarimetric`. Releases the GIL.");
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
        "Writes the synthetic sessions lab/ (blackbody, no polarizer), polcal/ (blackbody through the polarizer "
        "and a known source) and scene/ (a 300 K panel with ε_S0 = 0.93, ε_S1 = −0.035 in front of a 280 K "
        "background, an IR reflector at the left) of a simulated uncooled camera (calibration/synthetic_session.h); "
        "returns the true scene Stokes image S0 S1 S2.");
}

PixelRect rect_of(const py::handle& rect, const std::string& what) {
    const auto v = rect.cast<std::vector<int>>();
    if (v.size() != 4) fail("{}: expected a rectangle [x, y, width, height], got {} numbers", what, v.size());
    return {v[0], v[1], v[2], v[3]};
}

py::dict result_dict(const EmissivityResult& r) {
    py::dict d;
    d["name"] = r.name;
    d["view_angle_deg"] = r.view_angle_deg;
    d["temperature_k"] = r.temperature_k;
    d["pixels"] = r.pixels;
    d["l_dw_w_m2_sr"] = r.l_dw;
    d["l_bb_w_m2_sr"] = r.l_bb;
    d["eps_s0"] = r.eps_s0;
    d["eps_s0_2sigma"] = r.eps_s0_2sigma;
    d["eps_s1"] = r.eps_s1;
    d["eps_s1_2sigma"] = r.eps_s1_2sigma;
    d["eps_s2"] = r.eps_s2;
    d["eps_s2_2sigma"] = r.eps_s2_2sigma;
    d["warnings"] = r.warnings;
    return d;
}

void bind_emissivity(py::module_& m) {
    m.def(
        "extract_emissivity",
        [](const py::object& stokes, const py::object& reflector, const py::list& targets, const Band& band) {
            EmissivityRois rois;
            rois.reflector = rect_of(reflector, "reflector");
            for (const auto& t : targets) {
                const auto d = t.cast<py::dict>();
                EmissivityTarget target;
                target.name = d["name"].cast<std::string>();
                target.rect = rect_of(d["rect"], "targets['" + target.name + "'].rect");
                target.view_angle_deg = d["view_angle_deg"].cast<double>();
                if (d.contains("temperature_k")) target.temperature_k = d["temperature_k"].cast<double>();
                if (d.contains("temperature_std_k")) target.temperature_std_k = d["temperature_std_k"].cast<double>();
                if (d.contains("blackbody_rect"))
                    target.blackbody_rect =
                        rect_of(d["blackbody_rect"], "targets['" + target.name + "'].blackbody_rect");
                rois.targets.push_back(std::move(target));
            }
            const Image image = from_python(
                stokes, py::hasattr(stokes, "attributes") ? stokes.attr("attributes") : py::object(py::none()));
            py::list out;
            for (const auto& r : extract_emissivity(image, rois, band)) out.append(result_dict(r));
            return out;
        },
        py::arg("stokes"), py::arg("reflector"), py::arg("targets"), py::arg("band"),
        "Polarized emissivity of targets in a reduced Stokes image (paper eq 17): the IR reflector rectangle "
        "[x, y, w, h] gives the downwelling radiance, each target {name, rect, view_angle_deg, temperature_k "
        "(contact) or blackbody_rect, temperature_std_k} its ε_S0, ε_S1, ε_S2 with 2σ uncertainties — the rows "
        "fit_microfacet takes (ε_S1 in the plane-of-emission frame).");
}

/// A (T, H, W) cube of frames as a FrameStack.
FrameStack stack_of(const py::handle& cube) {
    const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(cube);
    if (!a || a.ndim() != 3) fail("frames: expected a 3-D array (frames, H, W)");
    FrameStack stack;
    stack.height = static_cast<int>(a.shape(1));
    stack.width = static_cast<int>(a.shape(2));
    const auto n = static_cast<std::size_t>(a.shape(1) * a.shape(2));
    for (py::ssize_t t = 0; t < a.shape(0); ++t)
        stack.frames.emplace_back(a.data() + static_cast<std::size_t>(t) * n,
                                  a.data() + static_cast<std::size_t>(t + 1) * n);
    validate_stack(stack, "frames");
    return stack;
}

void bind_noise(py::module_& m) {
    m.def(
        "three_d_noise",
        [](const py::object& frames, const std::string& convention) {
            if (convention != "population" && convention != "sample")
                fail("convention: expected 'population' or 'sample', got '{}'", convention);
            const FrameStack stack = stack_of(frames);
            const ThreeDNoise n =
                three_d_noise(stack, convention == "sample" ? NoiseConvention::Sample : NoiseConvention::Population);
            py::dict d;
            d["mean"] = n.mean;
            d["sigma_t"] = n.sigma_t;
            d["sigma_v"] = n.sigma_v;
            d["sigma_h"] = n.sigma_h;
            d["sigma_tv"] = n.sigma_tv;
            d["sigma_th"] = n.sigma_th;
            d["sigma_vh"] = n.sigma_vh;
            d["sigma_tvh"] = n.sigma_tvh;
            d["sigma_total"] = n.sigma_total;
            return d;
        },
        py::arg("frames"), py::arg("convention") = "population",
        "3D noise (D'Agostino & Webb, Proc. SPIE 1488, 1991) of a (frames, H, W) stack of a uniform source: mean "
        "and σ of the seven components t, v, h, tv, th, vh, tvh and their total. 'population' (Σx²/n: the "
        "variances add up to the cube's) or 'sample' (Σx²/(n − 1), as pyradi's ry3dnoise).");
    m.def(
        "temporal_noise",
        [](const py::object& frames) {
            const FrameStack stack = stack_of(frames);
            return array_from_plane(temporal_noise(stack), stack.width, stack.height);
        },
        py::arg("frames"), "Per-pixel temporal standard deviation (n − 1) of a (frames, H, W) stack → (H, W).");
}

}  // namespace

void bind_calibration_sessions(py::module_& m) {
    bind_noise(m);
    bind_radiometric(m);
    bind_session(m);
    bind_emissivity(m);
}

}  // namespace tirpol::python
