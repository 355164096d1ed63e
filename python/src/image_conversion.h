#pragma once
/// \file image_conversion.h
/// tirpol::Image ↔ tirpol.Image (the Python dict of channel name → float32 array (H, W) with an
/// `attributes` dict of EXR header attributes).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "tirpol/core/image.h"

namespace tirpol::python {

/// A float32 array of shape (height, width) that takes over `plane` without copying it.
pybind11::array_t<float> array_from_plane(std::vector<float>&& plane, int width, int height);

/// A 2-D array as C-contiguous float32: the array itself when it already is one (no copy), else a
/// converted copy. `what` names it in errors (tirpol::Error if it is not 2-D or its shape is not
/// (height, width) when those are > 0); sets width and height from the first array.
pybind11::array_t<float> float_plane(const pybind11::handle& array, const std::string& what,
                                     int& width, int& height);

/// float_plane's values copied into a plane the library can own.
std::vector<float> plane_from_array(const pybind11::handle& array, const std::string& what,
                                    int& width, int& height);

/// A tirpol.Image holding the channels of `image` (moved, not copied) in channel order.
pybind11::object to_python(Image&& image);

/// An Image from a mapping of channel name → 2-D array, and a mapping of header attributes
/// (int, float, str or a sequence of floats). tirpol::Error names the channel or attribute at
/// fault.
Image from_python(const pybind11::handle& channels, const pybind11::handle& attributes);

/// A tirpol.Image (its `attributes` too) or a plain dict of channel name → 2-D array as an Image.
Image image_from_python(const pybind11::handle& image);

}  // namespace tirpol::python
