#include "image_conversion.h"

#include <pybind11/stl.h>

#include <limits>
#include <memory>

#include "tirpol/core/error.h"

namespace py = pybind11;

namespace tirpol::python {

namespace {

py::object attribute_to_python(const AttributeValue& value) {
    return std::visit([](const auto& v) -> py::object { return py::cast(v); }, value);
}

AttributeValue attribute_from_python(const std::string& name, const py::handle& value) {
    const py::module_ numpy = py::module_::import("numpy");
    if (py::isinstance<py::bool_>(value) || py::isinstance(value, numpy.attr("bool_")))
        fail("attribute '{}': expected an int, a float, a str or a sequence of floats, got a bool",
             name);
    if (py::isinstance<py::int_>(value) || py::isinstance(value, numpy.attr("integer"))) {
        const auto v = value.cast<long long>();
        if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
            fail("attribute '{}': {} does not fit the EXR int attribute (32-bit)", name, v);
        return static_cast<int>(v);
    }
    if (py::isinstance<py::float_>(value) || py::isinstance(value, numpy.attr("floating")))
        return value.cast<double>();
    if (py::isinstance<py::str>(value)) return value.cast<std::string>();
    try {
        const auto list =
            py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
        if (list && list.ndim() == 1)
            return std::vector<double>(list.data(), list.data() + list.size());
    } catch (const py::error_already_set&) {
    }
    fail("attribute '{}': expected an int, a float, a str or a sequence of floats, got {}", name,
         py::str(py::type::of(value)).cast<std::string>());
}

}  // namespace

py::array_t<float> array_from_plane(std::vector<float>&& plane, int width, int height) {
    auto owner = std::make_unique<std::vector<float>>(std::move(plane));
    float* data = owner->data();
    py::capsule free_when_done(owner.get(),
                               [](void* p) { delete static_cast<std::vector<float>*>(p); });
    owner.release();
    return py::array_t<float>({static_cast<py::ssize_t>(height), static_cast<py::ssize_t>(width)},
                              data, free_when_done);
}

py::array_t<float> float_plane(const py::handle& array, const std::string& what, int& width,
                               int& height) {
    auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(array);
    if (!a)
        fail("{}: expected a 2-D array of numbers (H, W), got {}", what,
             py::str(py::type::of(array)).cast<std::string>());
    if (a.ndim() != 2) fail("{}: expected a 2-D array (H, W), got {} dimensions", what, a.ndim());
    const auto h = static_cast<int>(a.shape(0)), w = static_cast<int>(a.shape(1));
    if (width > 0 && (w != width || h != height))
        fail("{}: shape ({}, {}) differs from the first array's ({}, {})", what, h, w, height,
             width);
    width = w;
    height = h;
    return a;
}

std::vector<float> plane_from_array(const py::handle& array, const std::string& what, int& width,
                                    int& height) {
    const auto a = float_plane(array, what, width, height);
    return {a.data(), a.data() + a.size()};
}

py::object to_python(Image&& image) {
    py::dict channels;
    const int w = image.width(), h = image.height();
    for (const std::string& name : image.channel_names())
        channels[py::str(name)] = array_from_plane(std::move(image.channel(name)), w, h);
    py::dict attributes;
    for (const auto& [name, value] : image.attributes())
        attributes[py::str(name)] = attribute_to_python(value);
    return py::module_::import("tirpol.image").attr("Image")(channels, attributes);
}

namespace {
// A channel name as UTF-8: only str is a name (str(b"x") would silently become "b'x'"), and a str
// holding a lone surrogate (bytes decoded with surrogateescape) has no UTF-8 form. A NUL is refused
// by write_exr itself, whoever calls it.
std::string channel_name(const py::handle& key) {
    if (!py::isinstance<py::str>(key))
        fail("image: channel names must be str, got {} {}",
             py::str(py::type::of(key).attr("__name__")).cast<std::string>(),
             py::repr(key).cast<std::string>());
    PyObject* utf8 = PyUnicode_AsUTF8String(key.ptr());
    if (!utf8) {
        PyErr_Clear();
        fail("image: channel name {} is not valid UTF-8 (it holds a lone surrogate)",
             py::repr(key).cast<std::string>());
    }
    const auto bytes = py::reinterpret_steal<py::bytes>(utf8);
    return bytes.cast<std::string>();
}
}  // namespace

Image from_python(const py::handle& channels, const py::handle& attributes) {
    if (!py::isinstance<py::dict>(channels) && !py::hasattr(channels, "items"))
        fail("image: expected a mapping of channel name to 2-D array");
    int width = 0, height = 0;
    std::vector<std::pair<std::string, std::vector<float>>> planes;
    for (const auto& item : channels.attr("items")()) {
        const auto pair = item.cast<py::tuple>();
        const auto name = channel_name(pair[0]);
        planes.emplace_back(name,
                            plane_from_array(pair[1], "channel '" + name + "'", width, height));
    }
    if (planes.empty()) fail("image: no channels (an EXR needs at least one)");
    Image image(width, height);
    for (auto& [name, plane] : planes) image.set_channel(name, std::move(plane));
    if (!attributes.is_none())
        for (const auto& item : attributes.attr("items")()) {
            const auto pair = item.cast<py::tuple>();
            const auto name = py::str(pair[0]).cast<std::string>();
            image.attributes()[name] = attribute_from_python(name, pair[1]);
        }
    return image;
}

Image image_from_python(const py::handle& image) {
    return from_python(image, py::hasattr(image, "attributes") ? image.attr("attributes")
                                                               : py::object(py::none()));
}

}  // namespace tirpol::python
