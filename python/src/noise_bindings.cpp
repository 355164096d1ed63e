// tirpol.calibration, noise: 3D noise, temporal noise and NEDT maps of a (frames, H, W) stack.
#include <pybind11/numpy.h>

#include "bindings.h"
#include "image_conversion.h"
#include "tirpol/calibration/noise.h"
#include "tirpol/core/error.h"

namespace py = pybind11;

namespace tirpol::python {

namespace {

using namespace tirpol::calibration;

/// A (T, H, W) cube of frames as a FrameStack.
FrameStack stack_of(const py::handle& cube) {
    const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(cube);
    if (!a || a.ndim() != 3) fail("frames: expected a 3-D array (frames, H, W)");
    FrameStack stack;
    stack.height = static_cast<int>(a.shape(1));
    stack.width = static_cast<int>(a.shape(2));
    const auto n = static_cast<std::size_t>(a.shape(1) * a.shape(2));
    for (py::ssize_t t = 0; t < a.shape(0); ++t)
        stack.frames.emplace_back(a.data() + static_cast<std::size_t>(t) * n,
                                  a.data() + static_cast<std::size_t>(t + 1) * n);
    validate_stack(stack, "frames");
    return stack;
}

/// The responsivity as a plane of the stack's size: a number (uniform) or an (H, W) array.
std::vector<float> responsivity_plane(const py::object& responsivity, const FrameStack& stack) {
    if (py::isinstance<py::float_>(responsivity) || py::isinstance<py::int_>(responsivity))
        return std::vector<float>(
            static_cast<std::size_t>(stack.width) * static_cast<std::size_t>(stack.height),
            responsivity.cast<float>());
    int width = stack.width, height = stack.height;
    return plane_from_array(responsivity, "responsivity_per_k", width, height);
}

}  // namespace

void bind_noise(py::module_& m) {
    m.def(
        "three_d_noise",
        [](const py::object& frames, const std::string& convention) {
            if (convention != "population" && convention != "sample")
                fail("convention: expected 'population' or 'sample', got '{}'", convention);
            const FrameStack stack = stack_of(frames);
            const ThreeDNoise n =
                three_d_noise(stack, convention == "sample" ? NoiseConvention::Sample
                                                            : NoiseConvention::Population);
            py::dict d;
            d["mean"] = n.mean;
            d["sigma_t"] = n.sigma_t;
            d["sigma_v"] = n.sigma_v;
            d["sigma_h"] = n.sigma_h;
            d["sigma_tv"] = n.sigma_tv;
            d["sigma_th"] = n.sigma_th;
            d["sigma_vh"] = n.sigma_vh;
            d["sigma_tvh"] = n.sigma_tvh;
            d["sigma_total"] = n.sigma_total;
            return d;
        },
        py::arg("frames"), py::arg("convention") = "population",
        "3D noise (D'Agostino & Webb, Proc. SPIE 1488, 1991) of a (frames, H, W) stack of a "
        "uniform source: mean "
        "and σ of the seven components t, v, h, tv, th, vh, tvh and their total. 'population' "
        "(Σx²/n: the "
        "variances add up to the cube's) or 'sample' (Σx²/(n − 1), as pyradi's ry3dnoise).");
    m.def(
        "temporal_noise",
        [](const py::object& frames) {
            const FrameStack stack = stack_of(frames);
            return array_from_plane(temporal_noise(stack), stack.width, stack.height);
        },
        py::arg("frames"),
        "Per-pixel temporal standard deviation (n − 1) of a (frames, H, W) stack → (H, W).");
    m.def(
        "nedt_map",
        [](const py::object& frames, const py::object& responsivity_per_k) {
            const FrameStack stack = stack_of(frames);
            return array_from_plane(
                nedt_map(temporal_noise(stack), responsivity_plane(responsivity_per_k, stack)),
                stack.width, stack.height);
        },
        py::arg("frames"), py::arg("responsivity_per_k"),
        "Per-pixel NEDT (K) of a (frames, H, W) stack of a uniform source: temporal σ (n − 1) / "
        "responsivity, "
        "the responsivity in stack units per kelvin as a number or an (H, W) array (for counts: "
        "gain·dL/dT at the "
        "source temperature, e.g. cal.gain * band.radiance_dT(T)); NaN where it is not positive.");
    m.def(
        "nedt_vs_averaging",
        [](const py::object& frames, const py::object& responsivity_per_k) {
            const FrameStack stack = stack_of(frames);
            py::list out;
            for (const auto& p :
                 nedt_vs_averaging(stack, responsivity_plane(responsivity_per_k, stack)))
                out.append(py::dict(py::arg("frames_averaged") = p.frames_averaged,
                                    py::arg("median_nedt_k") = p.median_nedt_k,
                                    py::arg("white_noise_k") = p.white_noise_k));
            return out;
        },
        py::arg("frames"), py::arg("responsivity_per_k"),
        "NEDT against the number of frames averaged, n = 1, 2, 4, … while ≥ 4 independent n-frame "
        "means remain: "
        "[{'frames_averaged', 'median_nedt_k' (measured from the n-frame means), 'white_noise_k' "
        "(NEDT(1)/√n)}]. "
        "A measured curve above the white-noise one shows drift or 1/f noise.");
}

}  // namespace tirpol::python
