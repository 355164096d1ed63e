// The extension module tirpol._tirpol: errors at its top level, one submodule per library. The
// submodules are entered in sys.modules so that the pure-Python package can re-export them with
// `from ._tirpol.core import *` (pybind11's def_submodule alone does not make them importable).
#include <pybind11/pybind11.h>

#include "bindings.h"

namespace py = pybind11;

namespace {

py::module_ importable_submodule(py::module_& parent, const char* name, const char* doc) {
    py::module_ sub = parent.def_submodule(name, doc);
    py::module_::import("sys").attr("modules")[py::str(std::string("tirpol._tirpol.") + name)] = sub;
    return sub;
}

}  // namespace

PYBIND11_MODULE(_tirpol, m) {
    m.doc() = "tirpol's C++ library (pybind11). Use the package `tirpol`, which re-exports this module.";
    tirpol::python::bind_errors(m);
    py::module_ core = importable_submodule(m, "core", "Stokes/Mueller algebra, Planck radiometry, EXR I/O");
    tirpol::python::bind_core(core);
    py::module_ materials = importable_submodule(m, "materials", "Material files, polarized emissivity, Mueller pBRDF");
    tirpol::python::bind_materials(materials);
    py::module_ simulation = importable_submodule(m, "simulation", "Scenes and the polarized path tracer");
    tirpol::python::bind_simulation(simulation);
    py::module_ calibration = importable_submodule(m, "calibration", "Analyzer model and Stokes reduction");
    tirpol::python::bind_calibration(calibration);
    tirpol::python::bind_calibration_sessions(calibration);
    py::module_ fitting = importable_submodule(m, "fitting", "Fits of pBRDF parameters with uncertainties");
    tirpol::python::bind_fitting(fitting);
    py::module_ acquisition = importable_submodule(m, "acquisition", "Cameras by URI, frames as arrays");
    tirpol::python::bind_acquisition(acquisition);
    py::module_ report = importable_submodule(m, "report", "Measured-vs-simulated comparison and HTML report");
    tirpol::python::bind_report(report);
}
