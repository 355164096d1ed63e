// tirpol.calibration, microgrid part: the per-pixel analyzer calibration of a microgrid (DoFP)
// camera and its prepared reducer, numpy in and out, with the σ channels of the reduction.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <span>

#include "bindings.h"
#include "image_conversion.h"
#include "tirpol/calibration/microgrid_session.h"
#include "tirpol/calibration/synthetic_session.h"
#include "tirpol/core/error.h"

namespace py = pybind11;

namespace tirpol::python {

namespace {

using calibration::MicrogridPixelCalibration;
using calibration::MicrogridPixelReducer;

/// A plane of the calibration as a (H, W) float32 array (a copy: the calibration keeps its own).
py::array_t<float> plane_of(const MicrogridPixelCalibration& c, const std::vector<float>& plane) {
    return array_from_plane(std::vector<float>(plane), c.width, c.height);
}

/// A computed per-pixel quantity (transmission, diattenuation, axis) as a (H, W) array.
template <typename Per>
py::array_t<float> computed_plane(const MicrogridPixelCalibration& c, Per per_pixel) {
    std::vector<float> plane(static_cast<std::size_t>(c.width) *
                             static_cast<std::size_t>(c.height));
    for (std::size_t i = 0; i < plane.size(); ++i) plane[i] = per_pixel(i);
    return array_from_plane(std::move(plane), c.width, c.height);
}

void bind_pixel_calibration(py::module_& m) {
    py::class_<MicrogridPixelCalibration>(
        m, "MicrogridPixelCalibration",
        "Each pixel's analysis vector w_i = ½·t_i·(1, d_i cos 2θ_i, d_i sin 2θ_i) and background "
        "b_i of a microgrid camera (Powell & Gruev 2013; "
        "calibration/microgrid_pixel_calibration.h), "
        "planes (H, W) float32; its parameter uncertainties when known.")
        .def_readonly("width", &MicrogridPixelCalibration::width)
        .def_readonly("height", &MicrogridPixelCalibration::height)
        .def_readonly("fit_rms", &MicrogridPixelCalibration::fit_rms,
                      "RMS residual of the per-pixel fits, signal units")
        .def_readonly("stokes_units", &MicrogridPixelCalibration::stokes_units)
        .def_property_readonly(
            "w",
            [](const MicrogridPixelCalibration& c) {
                return py::make_tuple(plane_of(c, c.analysis[0]), plane_of(c, c.analysis[1]),
                                      plane_of(c, c.analysis[2]));
            },
            "(w0, w1, w2): the analysis vectors' components, signal per Stokes unit")
        .def_property_readonly(
            "background",
            [](const MicrogridPixelCalibration& c) { return plane_of(c, c.background); },
            "b_i, signal units")
        .def_property_readonly(
            "bad",
            [](const MicrogridPixelCalibration& c) {
                return c.bad.empty() ? py::object(py::none()) : py::object(plane_of(c, c.bad));
            },
            "BadPixel bit mask as float (0 = good), or None when no pixel was assessed")
        .def_property_readonly(
            "transmission",
            [](const MicrogridPixelCalibration& c) {
                return computed_plane(c, [&](std::size_t i) { return c.transmission(i); });
            },
            "t_i = 2·w_i0")
        .def_property_readonly(
            "diattenuation",
            [](const MicrogridPixelCalibration& c) {
                return computed_plane(c, [&](std::size_t i) { return c.diattenuation(i); });
            },
            "d_i = |(w_i1, w_i2)|/w_i0")
        .def_property_readonly(
            "axis_angle_deg",
            [](const MicrogridPixelCalibration& c) {
                return computed_plane(c, [&](std::size_t i) { return c.axis_angle_deg(i); });
            },
            "θ_i in degrees, [0, 180), camera frame")
        .def("has_uncertainties", &MicrogridPixelCalibration::has_uncertainties,
             "Whether the parameters' covariance is known (then reduction adds σ channels).")
        .def(
            "to_image", [](const MicrogridPixelCalibration& c) { return to_python(c.to_image()); },
            "The calibration as a tirpol.Image (the EXR `tirpol calibrate microgrid` writes; "
            "tirpol.core.write_exr writes it).")
        .def_static(
            "from_image",
            [](const py::handle& image) {
                return MicrogridPixelCalibration::from_image(image_from_python(image));
            },
            py::arg("image"),
            "The inverse of to_image (e.g. of tirpol.core.read_exr of a calibration file).");

    m.def(
        "calibrate_microgrid_pixels",
        [](const Eigen::MatrixX3d& source_stokes, const py::array& frames, bool fit_background) {
            const py::array_t<float, py::array::c_style | py::array::forcecast> stack(frames);
            if (stack.ndim() != 3)
                fail("frames: expected a (J, H, W) array of flat-field frames, got {} dimensions",
                     stack.ndim());
            if (stack.shape(0) != source_stokes.rows())
                fail(
                    "frames: {} flat-field frames for {} source Stokes vectors (rows of "
                    "source_stokes); expected one frame per source",
                    stack.shape(0), source_stokes.rows());
            const auto height = static_cast<int>(stack.shape(1));
            const auto width = static_cast<int>(stack.shape(2));
            const std::size_t n =
                static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
            std::vector<calibration::MicrogridFlatField> fields;
            for (Eigen::Index j = 0; j < source_stokes.rows(); ++j) {
                const float* first = stack.data() + static_cast<std::size_t>(j) * n;
                fields.push_back(
                    {source_stokes.row(j).transpose(), std::vector<float>(first, first + n)});
            }
            py::gil_scoped_release release;
            return calibration::calibrate_microgrid_pixels(fields, width, height, fit_background);
        },
        py::arg("source_stokes"), py::arg("frames"), py::arg("fit_background") = true,
        "Fits every pixel's analysis vector (and background) by least squares over flat fields of "
        "known Stokes: source_stokes (J, 3) rows (S0, S1, S2), frames (J, H, W) the frame-averaged "
        "mosaics. With more sources than parameters the result has uncertainties.");

    m.def(
        "calibrate_microgrid_sessions",
        [](const std::vector<std::filesystem::path>& sessions, const Band& band) {
            calibration::MicrogridFlatFieldCalibration result;
            {
                py::gil_scoped_release release;
                result = calibration::calibrate_microgrid_sessions(sessions, band);
            }
            py::dict out;
            out["bad_count"] = result.bad_count();
            out["gain_rel_spread"] = result.gain_rel_spread;
            out["diattenuation_median"] = result.diattenuation_median;
            out["diattenuation_spread"] = result.diattenuation_spread;
            out["axis_error_rms_deg"] = result.axis_error_rms_deg;
            out["pixels"] = std::move(result.pixels);
            out["nuc_only"] = std::move(result.nuc_only);
            return out;
        },
        py::arg("sessions"), py::arg("band"),
        "A microgrid camera's per-pixel calibration from flat-field sessions (two-point NUC, "
        "analyzers through a reference polarizer, bad pixels; docs/microgrid.md), as "
        "`tirpol calibrate microgrid` makes it: {pixels, nuc_only: MicrogridPixelCalibration, "
        "bad_count, gain_rel_spread, diattenuation_median, diattenuation_spread, "
        "axis_error_rms_deg}. `pixels` carries each pixel's parameter covariance.");

    py::class_<MicrogridPixelReducer>(
        m, "MicrogridPixelReducer",
        "A per-pixel calibration prepared for reducing many frames: each 2×2 super-pixel's 3×4 "
        "matrix made once, one matrix-vector product per cell per frame.")
        .def(py::init<const MicrogridPixelCalibration&>(), py::arg("calibration"))
        .def_property_readonly("width", &MicrogridPixelReducer::width)
        .def_property_readonly("height", &MicrogridPixelReducer::height)
        .def(
            "reduce",
            [](const MicrogridPixelReducer& r, const py::handle& mosaic,
               const py::object& mosaic_std) {
                int width = r.width(), height = r.height();
                const py::array_t<float> frame = float_plane(mosaic, "mosaic", width, height);
                py::array_t<float> sigma;
                if (!mosaic_std.is_none())
                    sigma = float_plane(mosaic_std, "mosaic_std", width, height);
                Image stokes;
                {
                    py::gil_scoped_release release;
                    const std::span<const float> frame_span(frame.data(),
                                                            static_cast<std::size_t>(frame.size()));
                    stokes =
                        mosaic_std.is_none()
                            ? r.reduce(frame_span)
                            : r.reduce(frame_span,
                                       std::span<const float>(
                                           sigma.data(), static_cast<std::size_t>(sigma.size())));
                }
                return to_python(std::move(stokes));
            },
            py::arg("mosaic"), py::arg("mosaic_std") = py::none(),
            "Reduces a (H, W) mosaic to a half-size tirpol.Image S0 S1 S2 DoLP AoP (deg), and "
            "S0_std S1_std S2_std DoLP_std AoP_std when the calibration has uncertainties or "
            "mosaic_std (each pixel's σ, e.g. of a frame mean) is given (attribute std_includes).");
}

void bind_synthetic(py::module_& m) {
    m.def(
        "write_synthetic_microgrid_sessions",
        [](const std::filesystem::path& root, const Band& band, const Eigen::Vector3d& scene_stokes,
           double analyzer_spread, unsigned seed) {
            calibration::SyntheticMicrogridCamera camera;
            camera.analyzer_spread = analyzer_spread;
            camera.seed = seed;
            py::gil_scoped_release release;
            calibration::write_synthetic_microgrid_flat_field(root / "flat", camera, band);
            calibration::write_synthetic_microgrid_scene(
                root / "scene", camera, calibration::uniform_stokes_scene(camera, scene_stokes));
        },
        py::arg("root"), py::arg("band"), py::arg("scene_stokes"), py::arg("analyzer_spread") = 0.1,
        py::arg("seed") = 1u,
        "Writes root/flat (the flat-field sessions of calibrate_microgrid_sessions) and root/scene "
        "(one record of a uniform scene of band-radiance Stokes (S0, S1, S2)) of the synthetic "
        "64×48 microgrid bolometer of the C++ tests (calibration/synthetic_microgrid.h: planted "
        "analyzer spread, gain/offset non-uniformity, noise 6 counts per frame, 16 frames per "
        "record, a dead, a hot and a noisy pixel).");
}

}  // namespace

void bind_microgrid_calibration(py::module_& m) {
    bind_pixel_calibration(m);
    bind_synthetic(m);
}

}  // namespace tirpol::python
