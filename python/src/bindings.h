#pragma once
/// \file bindings.h
/// One function per library: each adds its classes and functions to its submodule of tirpol._tirpol.

#include <pybind11/pybind11.h>

namespace tirpol::python {

void bind_errors(pybind11::module_& m);
void bind_core(pybind11::module_& m);
void bind_materials(pybind11::module_& m);
void bind_simulation(pybind11::module_& m);
void bind_calibration(pybind11::module_& m);
void bind_calibration_sessions(pybind11::module_& m);  ///< sessions and counts; called by bind_calibration
void bind_fitting(pybind11::module_& m);
void bind_acquisition(pybind11::module_& m);
void bind_report(pybind11::module_& m);

}  // namespace tirpol::python
