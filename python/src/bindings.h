#pragma once
/// \file bindings.h
/// One function per library: each adds its classes and functions to its submodule of
/// tirpol._tirpol.

#include <pybind11/pybind11.h>

namespace tirpol::python {

void bind_errors(pybind11::module_& m);
void bind_core(pybind11::module_& m);
void bind_materials(pybind11::module_& m);
void bind_simulation(pybind11::module_& m);
void bind_sensor_model(pybind11::module_& m);  ///< I(α) images; called by bind_simulation
void bind_calibration(pybind11::module_& m);
void bind_calibration_sessions(
    pybind11::module_& m);  ///< sessions and counts; called by bind_calibration
void bind_microgrid_calibration(
    pybind11::module_& m);              ///< per-pixel DoFP calibration; called by bind_calibration
void bind_noise(pybind11::module_& m);  ///< 3D noise, NEDT; called by bind_calibration
void bind_wire_grid(pybind11::module_& m);  ///< τ/B from arrays; called by bind_calibration
void bind_fitting(pybind11::module_& m);
void bind_render_fit(pybind11::module_& m);  ///< fit through the renderer; called by bind_fitting
void bind_acquisition(pybind11::module_& m);
void bind_capture(pybind11::module_& m);  ///< run_capture; called by bind_acquisition
void bind_report(pybind11::module_& m);

}  // namespace tirpol::python
