// tirpol.materials: material files and the library folder, polarized directional emissivity and the
// Mueller pBRDF evaluated for arrays of directions. Directions are surface-local (z = normal, both
// pointing away from the surface), Stokes frames those of materials/pbrdf.h (S1 > 0: s-polarized).
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <numbers>

#include "bindings.h"
#include "python_config.h"
#include "tirpol/core/error.h"
#include "tirpol/materials/emissivity.h"
#include "tirpol/materials/material.h"

namespace py = pybind11;

namespace tirpol::python {

namespace {

using materials::Material;
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// Shape (...) of an array of 3-vectors (..., 3); tirpol::Error naming `what` otherwise.
std::vector<py::ssize_t> vector_batch_shape(const DoubleArray& a, const char* what) {
    if (a.ndim() < 1 || a.shape(a.ndim() - 1) != 3)
        fail("{}: expected directions of shape (..., 3), got {} dimensions with last axis {}", what,
             a.ndim(), a.ndim() > 0 ? a.shape(a.ndim() - 1) : 0);
    return {a.shape(), a.shape() + a.ndim() - 1};
}

Vec3 unit_direction(const double* p, const char* what) {
    const Vec3 v(p[0], p[1], p[2]);
    if (!(v.norm() > 0.0) || !std::isfinite(v.norm()))
        fail("{}: a direction is zero or not finite", what);
    return v.normalized();
}

/// Applies `f(cos θ)` → Stokes for every angle of `theta_deg` (any shape); returns shape (..., 4).
template <typename F>
py::array_t<double> stokes_per_angle(const DoubleArray& theta_deg, F&& f) {
    std::vector<py::ssize_t> shape(theta_deg.shape(), theta_deg.shape() + theta_deg.ndim());
    shape.push_back(4);
    py::array_t<double> out(shape);
    double* o = out.mutable_data();
    for (py::ssize_t i = 0; i < theta_deg.size(); ++i, o += 4) {
        const double theta = theta_deg.data()[i];
        if (!(theta >= 0.0 && theta <= 90.0)) fail("theta_deg: {} is outside [0, 90]", theta);
        const StokesVector s = f(std::cos(theta * std::numbers::pi / 180.0));
        for (int k = 0; k < 4; ++k) o[k] = s[k];
    }
    return out;
}

py::dict parameters_of(const Material& m, double wavelength_um) {
    py::dict out;
    for (const auto& p : m.brdf->parameters(wavelength_um))
        out[py::str(p.name)] = py::make_tuple(p.value, p.unit);
    return out;
}

void bind_material(py::module_& m) {
    py::class_<Material>(m, "Material",
                         "A material: its polarized BRDF model, parameters and literature source.")
        .def_readonly("name", &Material::name)
        .def_readonly("source", &Material::source)
        .def_readonly("notes", &Material::notes)
        .def_readonly("file", &Material::file)
        .def_property_readonly("model", [](const Material& mat) { return mat.brdf->model(); })
        .def_property_readonly(
            "valid_wavelength_range_um",
            [](const Material& mat) { return mat.brdf->valid_wavelength_range_um(); })
        .def("parameters", &parameters_of, py::arg("wavelength_um"),
             "Model parameters at a wavelength: name → (value, unit).")
        .def(
            "emissivity",
            [](const Material& mat, const DoubleArray& theta_deg, double wavelength_um) {
                return stokes_per_angle(theta_deg, [&](double c) {
                    return materials::directional_emissivity(*mat.brdf, c, wavelength_um);
                });
            },
            py::arg("theta_deg"), py::arg("wavelength_um"),
            "Polarized directional emissivity ε(θ) = e0 − ∫M·e0 cosθi dωi (Gartley et al. eq 5 as "
            "Stokes) for "
            "emission angles theta_deg (any shape, degrees from the normal) → shape (..., 4), in "
            "the frame of "
            "the plane of emission: S1 < 0 is emission polarized in that plane.")
        .def(
            "reflected_stokes",
            [](const Material& mat, const DoubleArray& theta_deg, double wavelength_um) {
                return stokes_per_angle(theta_deg, [&](double c) {
                    return materials::hemispherical_reflected_stokes(*mat.brdf, c, wavelength_um);
                });
            },
            py::arg("theta_deg"), py::arg("wavelength_um"),
            "∫ M(ωi→ωo)·e0 cosθi dωi towards theta_deg under uniform unpolarized unit radiance → "
            "(..., 4); "
            "S0 is the directional-hemispherical reflectance (paper eq 2).")
        .def(
            "mueller_brdf",
            [](const Material& mat, const DoubleArray& wi, const DoubleArray& wo,
               double wavelength_um) {
                const auto batch = vector_batch_shape(wi, "wi");
                if (vector_batch_shape(wo, "wo") != batch) fail("wi and wo: shapes differ");
                auto shape = batch;
                shape.push_back(4);
                shape.push_back(4);
                py::array_t<double> out(shape);
                const std::size_t n = static_cast<std::size_t>(wi.size() / 3);
                double* o = out.mutable_data();
                for (std::size_t i = 0; i < n; ++i, o += 16) {
                    const MuellerMatrix mm =
                        mat.brdf->eval(unit_direction(wi.data() + 3 * i, "wi"),
                                       unit_direction(wo.data() + 3 * i, "wo"), wavelength_um);
                    for (int r = 0; r < 4; ++r)
                        for (int c = 0; c < 4; ++c) o[4 * r + c] = mm(r, c);
                }
                return out;
            },
            py::arg("wi"), py::arg("wo"), py::arg("wavelength_um"),
            "The Mueller pBRDF M(wi→wo) in 1/sr for arrays of surface-local directions of shape "
            "(..., 3) (z = "
            "normal, both away from the surface; normalised here) → (..., 4, 4). Incident Stokes "
            "in "
            "surface_frame(−wi, z), reflected in surface_frame(wo, z) (materials/pbrdf.h).")
        .def("__repr__", [](const Material& mat) {
            return fmt::format("<tirpol.materials.Material {} ({})>", mat.name, mat.brdf->model());
        });

    m.def("load_material", &materials::load_material, py::arg("path"),
          "Loads one material YAML file.");
    m.def(
        "material_from_dict",
        [](const py::dict& d, const std::filesystem::path& base_dir) {
            return materials::material_from_config(
                config_from_python(d, std::filesystem::absolute(base_dir).lexically_normal() /
                                          "<material from a Python dict>"));
        },
        py::arg("material"), py::arg("base_dir") = std::filesystem::path("."),
        "A material from a dict with the keys of a material file (docs/materials.md); relative "
        "data paths "
        "resolve against base_dir.");
    m.def(
        "load_library",
        [](const std::filesystem::path& directory) {
            const auto library = materials::MaterialLibrary::load_directory(directory);
            py::dict out;
            for (const auto& name : library.names()) out[py::str(name)] = library.get(name);
            return out;
        },
        py::arg("directory"),
        "Every material file of a folder (e.g. config/materials) as a dict name → Material.");
}

}  // namespace

void bind_materials(py::module_& m) { bind_material(m); }

}  // namespace tirpol::python
