// C++ exceptions → Python exceptions with the same message. tirpol::Error becomes tirpol.Error (a
// RuntimeError); its subclass tirpol::Cancelled becomes tirpol.Cancelled (a tirpol.Error).
// pybind11 tries translators newest first, so the subclass is registered after its base.
#include "bindings.h"
#include "tirpol/core/cancelled.h"
#include "tirpol/core/error.h"

namespace py = pybind11;

namespace tirpol::python {

void bind_errors(py::module_& m) {
    auto& error = py::register_exception<Error>(m, "Error", PyExc_RuntimeError);
    error.doc() =
        "Bad input to tirpol (a config, a file, an array of the wrong shape, a device reply). The message "
        "names the file, the field and what was expected, exactly as the C++ library and the CLI print it.";
    auto& cancelled = py::register_exception<Cancelled>(m, "Cancelled", error.ptr());
    cancelled.doc() = "A long computation was stopped by its cancellation flag before it finished.";
}

}  // namespace tirpol::python
