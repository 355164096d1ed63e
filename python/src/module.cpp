// The extension module tirpol._tirpol: errors at its top level, one submodule per library. The
// submodules are entered in sys.modules so that the pure-Python package can re-export them with
// `from ._tirpol.core import *` (pybind11's def_submodule alone does not make them importable).
#include <glog/logging.h>
#include <pybind11/pybind11.h>

#include "bindings.h"

namespace py = pybind11;

namespace {

struct Submodule {
    const char* name;
    const char* doc;
    void (*bind)(py::module_&);
};

// In dependency order: a submodule's functions may take classes of an earlier one (core.Band).
constexpr Submodule kSubmodules[] = {
    {"core", "Stokes/Mueller algebra, Planck radiometry, EXR I/O", tirpol::python::bind_core},
    {"materials", "Material files, polarized emissivity, Mueller pBRDF",
     tirpol::python::bind_materials},
    {"simulation", "Scenes and the polarized path tracer", tirpol::python::bind_simulation},
    {"calibration", "Analyzer model, radiometric calibration, Stokes reduction",
     tirpol::python::bind_calibration},
    {"fitting", "Fits of pBRDF parameters with uncertainties", tirpol::python::bind_fitting},
    {"acquisition", "Cameras and stages by URI, frames as arrays",
     tirpol::python::bind_acquisition},
    {"report", "Measured-vs-simulated comparison and HTML report", tirpol::python::bind_report},
};

}  // namespace

PYBIND11_MODULE(_tirpol, m) {
    m.doc() =
        "tirpol's C++ library (pybind11). Use the package `tirpol`, which re-exports this module.";
    // Ceres logs through glog, which, uninitialised, prefixes its first message with "WARNING:
    // Logging before InitGoogleLogging()". Initialise it as the CLI does: to stderr, errors only.
    if (!google::IsGoogleLoggingInitialized()) {
        FLAGS_logtostderr = true;
        FLAGS_minloglevel = google::GLOG_ERROR;
        google::InitGoogleLogging("tirpol");
    }
    tirpol::python::bind_errors(m);
    for (const Submodule& s : kSubmodules) {
        py::module_ sub = m.def_submodule(s.name, s.doc);
        py::module_::import("sys").attr(
            "modules")[py::str(std::string("tirpol._tirpol.") + s.name)] = sub;
        s.bind(sub);
    }
}
