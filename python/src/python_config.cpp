#include "python_config.h"

namespace py = pybind11;

namespace tirpol::python {

ConfigNode config_from_python(const py::handle& config, const std::filesystem::path& source_name) {
    // One key per line: the line numbers in messages then point at a readable dump of the dict.
    const auto text =
        py::module_::import("json")
            .attr("dumps")(config, py::arg("indent") = 1, py::arg("ensure_ascii") = false)
            .cast<std::string>();
    return ConfigNode::parse(text, source_name.string());
}

}  // namespace tirpol::python
