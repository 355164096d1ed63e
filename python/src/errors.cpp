// C++ exceptions → Python exceptions with the same message. tirpol::Error becomes tirpol.Error (a
// RuntimeError); its subclass tirpol::Cancelled becomes tirpol.Cancelled (a tirpol.Error).
// pybind11 tries translators newest first, so the subclass is registered after its base.
#include "bindings.h"
#include "device_errors.h"
#include "tirpol/core/error.h"
#include "tirpol/core/interrupt_signals.h"

namespace py = pybind11;

namespace tirpol::python {

void bind_errors(py::module_& m) {
    auto& error = py::register_exception<Error>(m, "Error", PyExc_RuntimeError);
    error.doc() =
        "Bad input to tirpol (a config, a file, an array of the wrong shape, a device reply). The "
        "message "
        "names the file, the field and what was expected, exactly as the C++ library and the CLI "
        "print it.";
    auto& cancelled = py::register_exception<Cancelled>(m, "Cancelled", error.ptr());
    cancelled.doc() = "A long computation was stopped by its cancellation flag before it finished.";
    static py::exception<DeviceFailure> device_error(m, "DeviceError", error.ptr());
    device_error.doc() =
        "A camera or stage failed (timeout, bad reply, fault, disconnected, ...): `code` names the "
        "kind, the "
        "message the device and what happened.";
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const DeviceFailure& e) {
            py::object instance = py::reinterpret_borrow<py::object>(device_error.ptr())(e.what());
            instance.attr("code") = e.code;
            PyErr_SetObject(device_error.ptr(), instance.ptr());
        }
    });
}

}  // namespace tirpol::python
