// tirpol.calibration: the analyzer model and Stokes reduction from numpy arrays.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <cstdint>
#include <span>

#include "bindings.h"
#include "image_conversion.h"
#include "interruptible.h"
#include "tirpol/calibration/analyzer.h"
#include "tirpol/calibration/microgrid_session.h"
#include "tirpol/calibration/microgrid_stokes.h"
#include "tirpol/calibration/stokes_reduction.h"
#include "tirpol/core/error.h"

namespace py = pybind11;

namespace tirpol::python {

namespace {

using calibration::AnalyzerModel;
using calibration::AnalyzerPosition;

void bind_analyzer(py::module_& m) {
    py::class_<AnalyzerPosition>(m, "AnalyzerPosition",
                                 "Model of one analyzer position (calibration/analyzer.h).")
        .def_readonly("nominal_angle_deg", &AnalyzerPosition::nominal_angle_deg)
        .def_readonly("axis_angle_deg", &AnalyzerPosition::axis_angle_deg)
        .def_readonly("diattenuation", &AnalyzerPosition::diattenuation)
        .def_readonly("relative_transmission", &AnalyzerPosition::relative_transmission)
        .def_readonly("background", &AnalyzerPosition::background)
        .def_property_readonly("extinction_ratio", &AnalyzerPosition::extinction_ratio);
    py::class_<AnalyzerModel>(
        m, "AnalyzerModel",
        "The rotating polarizer: one AnalyzerPosition per angle; its data-reduction matrix W⁺ "
        "turns N ≥ 3 analyzer images into (S0, S1, S2).")
        .def_static("ideal", &AnalyzerModel::ideal, py::arg("angles_deg"),
                    "An ideal polarizer at the given angles (for 0/45/90/135 the DRM is Gartley et "
                    "al. eqs 14–16).")
        .def_static("non_ideal", &AnalyzerModel::non_ideal, py::arg("angles_deg"),
                    py::arg("extinction_ratio"), py::arg("angle_offset_deg") = 0.0,
                    py::arg("t_max") = 1.0,
                    "A polarizer with an extinction ratio and an axis offset at every position.")
        .def_static(
            "estimate",
            [](const std::vector<double>& angles_deg, const Eigen::MatrixX3d& source_stokes,
               const Eigen::MatrixXd& intensities) {
                if (intensities.rows() != source_stokes.rows() ||
                    intensities.cols() != static_cast<Eigen::Index>(angles_deg.size()))
                    fail(
                        "intensities: expected shape ({}, {}) (one row per source, one column per "
                        "angle), got "
                        "({}, {})",
                        source_stokes.rows(), angles_deg.size(), intensities.rows(),
                        intensities.cols());
                std::vector<calibration::KnownSourceMeasurement> measurements;
                for (Eigen::Index j = 0; j < source_stokes.rows(); ++j) {
                    const Eigen::RowVectorXd row = intensities.row(j);
                    measurements.push_back(
                        {source_stokes.row(j).transpose(), {row.data(), row.data() + row.size()}});
                }
                return calibration::estimate_analyzer(angles_deg, measurements);
            },
            py::arg("angles_deg"), py::arg("source_stokes"), py::arg("intensities"),
            "Least-squares analyzer model from known polarized sources (the polarimetric "
            "calibration's analyzer "
            "step, from arrays): `source_stokes` (J, 3) = (S0, S1, S2) of each source in the "
            "camera frame, "
            "`intensities` (J, N) its mean measurement at each angle. Per position the axis angle, "
            "diattenuation, "
            "transmission and background are fitted; needs ≥ 4 sources spanning two intensities "
            "and two "
            "polarization orientations.")
        .def_readonly("positions", &AnalyzerModel::positions)
        .def("data_reduction_matrix", &AnalyzerModel::data_reduction_matrix, "W⁺, shape (3, N).")
        .def("condition_number", &AnalyzerModel::condition_number);
}

/// The analyzer images of `images` (angle_deg → (H, W) array) with their σ from `stds` (same keys),
/// as views of float32 arrays kept in `arrays`: float32 C-contiguous inputs are not copied (the
/// overhead bench/python_bench.cpp measures).
std::vector<calibration::AnalyzerPlanes> analyzer_planes(const py::dict& images,
                                                         const py::object& stds,
                                                         std::vector<py::array_t<float>>& arrays,
                                                         int& width, int& height) {
    const auto view = [&](const py::handle& value, const std::string& what) {
        arrays.push_back(float_plane(value, what, width, height));
        return std::span<const float>(arrays.back().data(),
                                      static_cast<std::size_t>(arrays.back().size()));
    };
    std::vector<calibration::AnalyzerPlanes> out;
    for (const auto& [key, value] : images) {
        calibration::AnalyzerPlanes a;
        // Keys are angles as numbers ({0: I0, 45: I45, ...}); a string key is the usual slip.
        if (!py::isinstance<py::int_>(key) && !py::isinstance<py::float_>(key))
            fail(
                "images: key {} is a {}; the keys are analyzer angles in degrees as numbers, e.g. "
                "{{0: i0, 45: i45, 90: i90, 135: i135}}",
                py::repr(key).cast<std::string>(),
                py::type::of(key).attr("__name__").cast<std::string>());
        a.angle_deg = key.cast<double>();
        a.source = fmt::format("images[{}]", a.angle_deg);
        a.signal = view(value, a.source);
        if (!stds.is_none()) {
            const auto std_dict = stds.cast<py::dict>();
            if (!std_dict.contains(key))
                fail("stds: no array for angle {} (every image needs its σ, or pass none)",
                     a.angle_deg);
            a.signal_std = view(std_dict[key], fmt::format("stds[{}]", a.angle_deg));
        }
        out.push_back(std::move(a));
    }
    if (out.empty()) fail("images: no analyzer images (expected a dict angle_deg → 2-D array)");
    return out;
}

void bind_reduce(py::module_& m) {
    m.def(
        "reduce",
        [](const py::dict& images, const py::object& stds, std::optional<AnalyzerModel> model,
           bool project_to_realizable, bool include_slar, const std::string& units,
           const calibration::WireGridCalibration* wire_grid) {
            int width = 0, height = 0;
            std::vector<py::array_t<float>>
                arrays;  // owns what the views see until the end of the call
            const auto inputs = analyzer_planes(images, stds, arrays, width, height);
            if (!model) {
                std::vector<double> angles;
                for (const auto& a : inputs) angles.push_back(a.angle_deg);
                std::sort(angles.begin(), angles.end());
                model = AnalyzerModel::ideal(angles);
            }
            calibration::ReductionOptions options;
            options.project_to_realizable = project_to_realizable;
            options.include_slar = include_slar;
            options.units = units;
            Image result = run_interruptible([&](const std::atomic<bool>& cancel) {
                calibration::ReductionOptions o = options;
                o.cancel = &cancel;
                return calibration::reduce_stokes(inputs, width, height, *model, wire_grid, o);
            });
            return to_python(std::move(result));
        },
        py::arg("images"), py::arg("stds") = py::none(), py::arg("model") = py::none(),
        py::arg("project_to_realizable") = true, py::arg("include_slar") = false,
        py::arg("units") = "W/(m^2 sr)", py::arg("wire_grid") = py::none(),
        "Stokes reduction S = W⁺·I per pixel (Tyo et al. 2006 §4) of analyzer images {angle_deg: "
        "(H, W) array}, "
        "with σ images `stds` (same keys) propagated to S0_std S1_std S2_std DoLP_std AoP_std. "
        "Default model: an "
        "ideal polarizer at the given angles. Returns a tirpol.Image with S0 S1 S2 DoLP AoP "
        "(camera frame, "
        "S1 = I0 − I90, S2 = I45 − I135). With `wire_grid` (fit_wire_grid), each image is first "
        "corrected to "
        "L_SLAR = (I − B)/τ and the grid fit's covariance adds to the σ. Releases the GIL; Ctrl-C "
        "stops it "
        "(KeyboardInterrupt).");
}

/// A pattern given as "sony", "90,45,135,0" or four numbers.
calibration::MicrogridPattern pattern_from_python(const py::object& pattern) {
    if (py::isinstance<py::str>(pattern))
        return calibration::MicrogridPattern::parse(pattern.cast<std::string>(), "pattern");
    return calibration::MicrogridPattern(pattern.cast<std::array<double, 4>>(), "pattern");
}

void bind_microgrid(py::module_& m) {
    m.def(
        "demosaic",
        [](const py::handle& mosaic, const py::object& pattern, const std::string& method) {
            int width = 0, height = 0;
            const py::array_t<float> frame = float_plane(mosaic, "mosaic", width, height);
            const auto parsed_pattern = pattern_from_python(pattern);
            const auto parsed_method = calibration::parse_demosaic_method(method, "method");
            calibration::DemosaicedFrame planes;
            {
                py::gil_scoped_release release;
                planes = calibration::demosaic_microgrid(
                    std::span<const float>(frame.data(), static_cast<std::size_t>(frame.size())),
                    width, height, parsed_pattern, parsed_method, "mosaic");
            }
            py::dict out;
            for (std::size_t k = 0; k < 4; ++k)
                out[py::float_(planes.angles_deg[k])] =
                    array_from_plane(std::move(planes.planes[k]), planes.width, planes.height);
            return out;
        },
        py::arg("mosaic"), py::arg("pattern") = "sony", py::arg("method") = "newton",
        "Demosaics a microgrid (division-of-focal-plane) frame, a (H, W) array (float in, float "
        "out: no 8/16-bit round trip), into {angle_deg: (H, W) array} for the pattern's four "
        "analyzer angles (half size for method='super-pixel'). `pattern`: 'sony' (90,45,135,0), "
        "'a,b,c,d' or four angles for cell positions (0,0),(0,1),(1,0),(1,1); `method`: "
        "'super-pixel', 'bilinear' or 'newton' (docs/microgrid.md).");
    m.def(
        "reduce_microgrid",
        [](const py::handle& mosaic, const py::object& pattern, const std::string& method,
           const std::string& units) {
            const auto parsed_pattern = pattern_from_python(pattern);
            calibration::MicrogridReductionOptions options;
            options.method = calibration::parse_demosaic_method(method, "method");
            options.reduction.units = units;
            options.source = "mosaic";
            Image stokes;
            // A camera's uint16 frame is read where it lies (no float copy); anything else goes
            // through float32.
            using Counts = py::array_t<std::uint16_t, py::array::c_style>;
            if (py::isinstance<Counts>(mosaic) &&
                py::reinterpret_borrow<Counts>(mosaic).ndim() == 2) {
                const auto frame = py::reinterpret_borrow<Counts>(mosaic);
                const auto height = static_cast<int>(frame.shape(0));
                const auto width = static_cast<int>(frame.shape(1));
                py::gil_scoped_release release;
                stokes = calibration::reduce_microgrid(
                    std::span<const std::uint16_t>(frame.data(),
                                                   static_cast<std::size_t>(frame.size())),
                    width, height, parsed_pattern, options);
            } else {
                int width = 0, height = 0;
                const py::array_t<float> frame = float_plane(mosaic, "mosaic", width, height);
                py::gil_scoped_release release;
                stokes = calibration::reduce_microgrid(
                    std::span<const float>(frame.data(), static_cast<std::size_t>(frame.size())),
                    width, height, parsed_pattern, options);
            }
            return to_python(std::move(stokes));
        },
        py::arg("mosaic"), py::arg("pattern") = "sony", py::arg("method") = "newton",
        py::arg("units") = "counts",
        "Demosaics a microgrid frame and reduces it with ideal analyzers at the pattern's angles "
        "in "
        "one pass: a tirpol.Image with S0 S1 S2 DoLP AoP (camera frame, S1 = I0 − I90, "
        "S2 = I45 − I135). A C-contiguous uint16 (H, W) array is read without a copy.");
    m.def(
        "reduce_microgrid_session",
        [](const std::filesystem::path& session, const std::string& method,
           const std::optional<calibration::MicrogridPixelCalibration>& pixel_calibration) {
            calibration::MicrogridSessionOptions options;
            options.method = calibration::parse_demosaic_method(method, "method");
            options.pixel_calibration = pixel_calibration;
            return to_python(calibration::reduce_microgrid_session(session, options));
        },
        py::arg("session"), py::arg("method") = "newton", py::arg("pixel_calibration") = py::none(),
        "A microgrid camera's capture session (its manifest records the pattern): the records' "
        "mean mosaic demosaiced and reduced, as `tirpol reduce SESSION` does; with a "
        "MicrogridPixelCalibration, per super-pixel with S0_std … AoP_std from the records' "
        "temporal σ and the calibration's uncertainties (--pixel-calibration).");
}

}  // namespace

void bind_calibration(py::module_& m) {
    bind_microgrid(m);
    bind_microgrid_calibration(m);
    bind_analyzer(m);
    bind_wire_grid(m);
    bind_reduce(m);
    bind_calibration_sessions(m);
    bind_noise(m);
}

}  // namespace tirpol::python
