// tirpol.calibration, wire grid: the per-pixel τ(α), B(α) of the polarizer in front of the camera
// fitted from blackbody frames given as arrays (the polarimetric calibration without a session).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>

#include "bindings.h"
#include "image_conversion.h"
#include "tirpol/calibration/stokes_reduction.h"
#include "tirpol/core/error.h"

namespace py = pybind11;

namespace tirpol::python {

namespace {

using namespace tirpol::calibration;

/// One map of position `angle_deg` as an (H, W) array (a copy: the calibration keeps its own);
/// `square_root`: of a variance map, the standard uncertainty.
py::array_t<float> map_of(const WireGridCalibration& cal, double angle_deg,
                          std::vector<float> WireGridPosition::*map, bool square_root = false) {
    const WireGridPosition& p = cal.at(angle_deg);
    if ((p.*map).empty())
        fail("wire grid at {}°: no covariance (the frames had no σ images)", angle_deg);
    std::vector<float> values = p.*map;
    if (square_root)
        for (float& v : values) v = std::sqrt(v);
    return array_from_plane(std::move(values), cal.width, cal.height);
}

}  // namespace

void bind_wire_grid(py::module_& m) {
    py::class_<WireGridCalibration>(
        m, "WireGridCalibration",
        "Per-pixel transmittance τ(α) and additive background B(α) of the wire grid at "
        "each analyzer angle (calibration/wire_grid.h): I(α) = τ(α)·a(α)·S + B(α).")
        .def_readonly("width", &WireGridCalibration::width)
        .def_readonly("height", &WireGridCalibration::height)
        .def_property_readonly("angles_deg",
                               [](const WireGridCalibration& c) {
                                   std::vector<double> angles;
                                   for (const auto& p : c.positions) angles.push_back(p.angle_deg);
                                   return angles;
                               })
        .def(
            "tau",
            [](const WireGridCalibration& c, double a) {
                return map_of(c, a, &WireGridPosition::tau);
            },
            py::arg("angle_deg"), "τ (H, W), dimensionless.")
        .def(
            "background",
            [](const WireGridCalibration& c, double a) {
                return map_of(c, a, &WireGridPosition::background);
            },
            py::arg("angle_deg"), "B (H, W), units of the signal.")
        .def(
            "residual_rms",
            [](const WireGridCalibration& c, double a) {
                return map_of(c, a, &WireGridPosition::residual_rms);
            },
            py::arg("angle_deg"), "RMS of the fit residuals (H, W), units of the signal.")
        .def(
            "tau_std",
            [](const WireGridCalibration& c, double a) {
                return map_of(c, a, &WireGridPosition::tau_var, true);
            },
            py::arg("angle_deg"), "Standard uncertainty of τ (H, W) from the frames' σ images.")
        .def(
            "background_std",
            [](const WireGridCalibration& c, double a) {
                return map_of(c, a, &WireGridPosition::background_var, true);
            },
            py::arg("angle_deg"), "Standard uncertainty of B (H, W) from the frames' σ images.");
    m.def(
        "fit_wire_grid",
        [](const py::dict& frames, const Band& band, const py::object& stds) {
            int width = 0, height = 0;
            std::vector<PolarizedBlackbodyFrame> inputs;
            for (const auto& [key, value] : frames) {
                const auto [angle_deg, temperature_k] = key.cast<std::pair<double, double>>();
                PolarizedBlackbodyFrame f;
                f.angle_deg = angle_deg;
                f.temperature_k = temperature_k;
                f.source = fmt::format("frames[({}, {})]", angle_deg, temperature_k);
                f.signal = plane_from_array(value, f.source, width, height);
                if (!stds.is_none()) {
                    const auto std_dict = stds.cast<py::dict>();
                    if (!std_dict.contains(key))
                        fail("stds: no array for {} (every frame needs its σ, or pass none)",
                             f.source);
                    f.signal_std =
                        plane_from_array(std_dict[key], "stds" + f.source.substr(6), width, height);
                }
                inputs.push_back(std::move(f));
            }
            if (inputs.empty())
                fail(
                    "frames: no blackbody frames (expected a dict (angle_deg, temperature_k) → 2-D "
                    "array)");
            py::gil_scoped_release release;
            return fit_wire_grid(inputs, width, height, band);
        },
        py::arg("frames"), py::arg("band"), py::arg("stds") = py::none(),
        "Fits τ(α) and B(α) per pixel, signal = τ·½·L_band(T) + B, to blackbody frames through the "
        "polarizer given "
        "as {(angle_deg, temperature_k): (H, W) array} (radiance from a radiometric calibration, "
        "or counts), ≥ 2 "
        "temperatures per angle; with σ images `stds` (same keys) also the τ/B covariance. Pass "
        "the result to "
        "reduce(..., wire_grid=) to remove the grid (L_SLAR = (I − B)/τ).");
}

}  // namespace tirpol::python
