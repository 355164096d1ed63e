// tirpol.simulation.sensor_images: the images I(α) the field camera would record through its
// non-ideal rotating analyzer (simulation/sensor_model.h) from a rendered Stokes image.
#include <pybind11/stl.h>

#include "bindings.h"
#include "image_conversion.h"
#include "python_config.h"
#include "tirpol/simulation/sensor_model.h"

namespace py = pybind11;

namespace tirpol::python {

void bind_sensor_model(py::module_& m) {
    m.def(
        "sensor_images",
        [](const py::object& stokes, const Band& band, const py::dict& model,
           std::uint64_t frame_index) {
            const auto sensor = simulation::SensorModel::from_config(
                config_from_python(model, "<dict sensor model>"));
            const Image image = image_from_python(stokes);
            std::vector<Image> images;
            {
                py::gil_scoped_release release;
                images = simulation::polarizer_images(image, sensor, band, frame_index);
            }
            py::list out;
            for (auto& i : images) out.append(to_python(std::move(i)));
            return out;
        },
        py::arg("stokes"), py::arg("band"), py::arg("model") = py::dict(),
        py::arg("frame_index") = 0,
        "The images the camera records through its rotating wire grid (paper §3.1), one "
        "tirpol.Image per analyzer "
        "angle: channel `radiance` I(α) = [P(α + offset)·S]₀ + ρ_grid·L_reflected + "
        "ε_grid·L_bb(T_grid) "
        "(W/(m²·sr)), P a linear diattenuator of transmittance τ and extinction ratio τ/τ_min, and "
        "with a `counts` "
        "model also `counts` = gain·I + offset + N(0, σ), σ = gain·NEDT·dL/dT(T_ref); attribute "
        "polarizer_angle_deg. `stokes` needs S0 S1 S2 S3 (camera frame, e.g. render()'s output). "
        "`model` has the "
        "keys of the --sensor YAML (docs/simulation.md): analyzer {angles_deg, transmission, "
        "extinction_ratio, "
        "angle_offset_deg}, background {reflectance, reflected_radiance, emissivity, temperature}, "
        "counts "
        "{gain_counts_per_radiance, offset_counts, nedt_k, reference_temperature}, seed. "
        "`frame_index` picks an "
        "independent noise realisation (consecutive frames).");
}

}  // namespace tirpol::python
