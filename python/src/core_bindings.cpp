// tirpol.core: Stokes helpers over arrays of Stokes vectors, Mueller matrices of standard elements,
// Planck radiometry (vectorised over numpy arrays) and EXR files as tirpol.Image dicts. Angles are
// in degrees at this boundary (ARCHITECTURE.md: degrees in configs and outputs), radians inside.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <numbers>

#include "bindings.h"
#include "image_conversion.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/core/stokes.h"

namespace py = pybind11;

namespace tirpol::python {

namespace {

using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

double deg_to_rad(double angle_deg) { return angle_deg * std::numbers::pi / 180.0; }

/// Applies `f` to every Stokes vector of an array of shape (..., 4), or (..., 3) for linear Stokes
/// (S3 = 0); returns an array of shape (...).
template <typename T, typename F>
py::array_t<T> map_stokes(const DoubleArray& s, const char* function, F&& f) {
    const py::ssize_t n = s.ndim() > 0 ? s.shape(s.ndim() - 1) : 0;
    if (n != 3 && n != 4)
        fail(
            "{}: expected Stokes vectors along the last axis, shape (..., 4) or (..., 3), got last "
            "axis {}",
            function, n);
    std::vector<py::ssize_t> shape(s.shape(), s.shape() + s.ndim() - 1);
    py::array_t<T> out(shape);
    const double* in = s.data();
    T* o = out.mutable_data();
    for (py::ssize_t i = 0; i < out.size(); ++i, in += n)
        o[i] = f(StokesVector(in[0], in[1], in[2], n == 4 ? in[3] : 0.0));
    return out;
}

/// Stokes vectors from what a user passes: an array of shape (..., 4) or (..., 3), or a
/// tirpol.Image (or dict) with channels S0, S1, S2 (and S3 if present), read as an (H, W, 4) array.
/// Complex or non-numeric input is refused with a message naming `function`.
DoubleArray stokes_argument(const py::object& value, const char* function) {
    if (py::isinstance<py::dict>(value)) {
        const py::dict channels = value.cast<py::dict>();
        for (const char* c : {"S0", "S1", "S2"})
            if (!channels.contains(c))
                fail(
                    "{}: the image has no channel {}; expected a tirpol.Image with S0, S1, S2 (a "
                    "reduced or rendered image) or an array of Stokes vectors (..., 4)",
                    function, c);
        const py::module_ np = py::module_::import("numpy");
        py::list planes;
        for (const char* c : {"S0", "S1", "S2"}) planes.append(channels[c]);
        planes.append(channels.contains("S3") ? channels["S3"]
                                              : np.attr("zeros_like")(channels["S0"]));
        return stokes_argument(np.attr("stack")(planes, py::arg("axis") = -1), function);
    }
    const py::module_ np = py::module_::import("numpy");
    const py::object array = np.attr("asarray")(value);
    const std::string kind = array.attr("dtype").attr("kind").cast<std::string>();
    if (kind == "c")
        fail(
            "{}: got complex values; Stokes vectors are real (pass .real if the imaginary part is "
            "zero)",
            function);
    if (kind != "f" && kind != "i" && kind != "u" && kind != "b")
        fail(
            "{}: expected an array of Stokes vectors (..., 4) or (..., 3) or a tirpol.Image with "
            "S0, S1, S2; got {} of dtype {}",
            function, py::type::of(value).attr("__name__").cast<std::string>(),
            py::str(array.attr("dtype")).cast<std::string>());
    return DoubleArray::ensure(array);
}

void bind_stokes(py::module_& m) {
    m.def(
        "dolp",
        [](const py::object& stokes) {
            const DoubleArray s = stokes_argument(stokes, "dolp");
            return map_stokes<double>(s, "dolp", [](const auto& v) { return dolp(v); });
        },
        py::arg("stokes"),
        "Degree of linear polarization √(S1²+S2²)/S0 of Stokes vectors of shape (..., 4) or (..., "
        "3); 0 where S0 ≤ 0, "
        "NaN where a component is NaN (an unmeasured pixel is not an unpolarized one).");
    m.def(
        "dop",
        [](const py::object& stokes) {
            const DoubleArray s = stokes_argument(stokes, "dop");
            return map_stokes<double>(s, "dop", [](const auto& v) { return dop(v); });
        },
        py::arg("stokes"),
        "Degree of polarization √(S1²+S2²+S3²)/S0 of Stokes vectors of shape (..., 4); 0 where S0 "
        "≤ 0, NaN where a "
        "component is NaN.");
    m.def(
        "aop_deg",
        [](const py::object& stokes) {
            const DoubleArray s = stokes_argument(stokes, "aop_deg");
            return map_stokes<double>(s, "aop_deg", [](const auto& v) { return aop_deg_0_180(v); });
        },
        py::arg("stokes"),
        "Angle of linear polarization ½·atan2(S2, S1) in degrees, in [0, 180) (the AoP image "
        "channel's convention), "
        "counter-clockwise from the frame's reference axis looking into the beam.");
    m.def(
        "is_realizable",
        [](const py::object& stokes) {
            const DoubleArray s = stokes_argument(stokes, "is_realizable");
            return map_stokes<bool>(s, "is_realizable",
                                    [](const auto& v) { return is_realizable(v, 1e-9); });
        },
        py::arg("stokes"),
        "S0 ≥ 0 and S0 ≥ √(S1²+S2²+S3²) (relative tolerance 1e-9), per Stokes vector.");
    m.def(
        "linearly_polarized",
        [](double s0, double dolp_value, double aop_deg) {
            return linearly_polarized(s0, dolp_value, deg_to_rad(aop_deg));
        },
        py::arg("s0"), py::arg("dolp"), py::arg("aop_deg"),
        "Stokes vector (4,) of intensity s0, degree of linear polarization dolp, angle aop_deg.");
}

void bind_mueller(py::module_& m) {
    m.def(
        "frame_rotation", [](double angle_deg) { return frame_rotation(deg_to_rad(angle_deg)); },
        py::arg("angle_deg"),
        "Mueller matrix (4, 4) rotating the Stokes reference frame by angle_deg counter-clockwise "
        "looking into the "
        "beam (Gartley et al. eq 11).");
    m.def(
        "rotate_element",
        [](const MuellerMatrix& mm, double angle_deg) {
            return rotate_element(mm, deg_to_rad(angle_deg));
        },
        py::arg("mueller"), py::arg("angle_deg"),
        "The element `mueller` physically rotated by angle_deg: R(−θ)·M·R(θ).");
    m.def(
        "linear_polarizer", [](double axis_deg) { return linear_polarizer(deg_to_rad(axis_deg)); },
        py::arg("axis_deg"),
        "Ideal linear polarizer with its transmission axis at axis_deg (Malus's law).");
    m.def(
        "linear_diattenuator",
        [](double axis_deg, double t_max, double t_min) {
            return linear_diattenuator(deg_to_rad(axis_deg), t_max, t_min);
        },
        py::arg("axis_deg"), py::arg("t_max"), py::arg("t_min"),
        "Linear diattenuator with intensity transmittances t_max along, t_min across the axis "
        "(Chipman et al. 2018, "
        "eq 6.35).");
    m.def(
        "polarizer_with_extinction",
        [](double axis_deg, double transmission, double extinction_ratio) {
            return polarizer_with_extinction(deg_to_rad(axis_deg), transmission, extinction_ratio);
        },
        py::arg("axis_deg"), py::arg("transmission"), py::arg("extinction_ratio"),
        "Non-ideal polarizer: major transmittance and extinction ratio t_max/t_min (400 for the "
        "paper's wire grid).");
    m.def(
        "linear_retarder",
        [](double fast_axis_deg, double retardance_deg) {
            return linear_retarder(deg_to_rad(fast_axis_deg), deg_to_rad(retardance_deg));
        },
        py::arg("fast_axis_deg"), py::arg("retardance_deg"),
        "Linear retarder (Collett's form, exp(i(ωt − kz)) convention: a quarter-wave plate at +45° "
        "turns horizontal "
        "light into S3 = −1).");
    m.def("depolarizer", &depolarizer, py::arg("retained_fraction"),
          "Partial depolarizer diag(1, a, a, a).");
    m.def("mueller_from_jones", &mueller_from_jones, py::arg("jones"),
          "Mueller matrix (4, 4) of a complex Jones matrix (2, 2), M_ij = ½·tr(σ_i J σ_j J†) "
          "(Chipman et al. eq 6.99).");
    m.def("is_physically_realizable", &is_physically_realizable, py::arg("mueller"),
          py::arg("rel_tol") = 1e-9,
          "Every eigenvalue of the Cloude coherency matrix ≥ −rel_tol·m00 (Cloude 1986).");
}

/// `f(x)` over a number or an array of any shape (numpy broadcasting rules of py::vectorize).
template <typename F>
py::object vectorized(F&& f, const py::object& x) {
    return py::vectorize([&f](double v) { return f(v); })(x.cast<py::array_t<double>>());
}

void bind_radiometry(py::module_& m) {
    m.def("planck_radiance", py::vectorize([](double wavelength_um, double temperature_k) {
              // NaN passes through (NaN in, NaN out); a wavelength ≤ 0 is a mistake, not a zero.
              if (wavelength_um <= 0.0)
                  fail("planck_radiance: wavelength_um must be > 0 µm, got {}", wavelength_um);
              return planck_radiance(wavelength_um, temperature_k);
          }),
          py::arg("wavelength_um"), py::arg("temperature_k"),
          "Planck spectral radiance W/(m²·sr·µm) of a blackbody (CODATA 2018 constants); arrays "
          "broadcast.");
    py::class_<Band>(
        m, "Band",
        "A spectral band [lo_um, hi_um] µm with an optional relative spectral response (RSR).")
        .def(py::init([](double lo_um, double hi_um,
                         std::optional<std::vector<double>> rsr_wavelength_um,
                         std::optional<std::vector<double>> rsr_response) {
                 if (rsr_wavelength_um.has_value() != rsr_response.has_value())
                     fail("Band: give both rsr_wavelength_um and rsr_response, or neither");
                 std::optional<SpectralResponse> rsr;
                 if (rsr_wavelength_um) rsr.emplace(*rsr_wavelength_um, *rsr_response);
                 return Band(lo_um, hi_um, std::move(rsr));
             }),
             py::arg("lo_um"), py::arg("hi_um"), py::arg("rsr_wavelength_um") = py::none(),
             py::arg("rsr_response") = py::none())
        .def_property_readonly("lo_um", &Band::lo_um)
        .def_property_readonly("hi_um", &Band::hi_um)
        .def_property_readonly("effective_width_um", &Band::effective_width_um,
                               "∫ R(λ) dλ over the band, µm.")
        .def(
            "radiance",
            [](const Band& b, const py::object& t) {
                return vectorized([&b](double v) { return b.radiance(v); }, t);
            },
            py::arg("temperature_k"),
            "Band radiance ∫ R(λ) L_bb(λ, T) dλ in W/(m²·sr), for a number or an array.")
        .def(
            "radiance_dT",
            [](const Band& b, const py::object& t) {
                return vectorized([&b](double v) { return b.radiance_dT(v); }, t);
            },
            py::arg("temperature_k"), "d(band radiance)/dT in W/(m²·sr·K).")
        .def(
            "brightness_temperature",
            [](const Band& b, const py::object& l) {
                return vectorized([&b](double v) { return b.brightness_temperature(v); }, l);
            },
            py::arg("radiance_w_m2_sr"),
            "The temperature (K) whose band radiance equals the given one, to 1e-6 K; NaN for "
            "radiance ≤ 0 or not "
            "finite. Inverse of radiance().")
        .def("__repr__", [](const Band& b) {
            return fmt::format("Band(lo_um={}, hi_um={}{})", b.lo_um(), b.hi_um(),
                               b.rsr() ? ", with RSR" : "");
        });
}

void bind_exr(py::module_& m) {
    m.def(
        "read_exr", [](const std::filesystem::path& path) { return to_python(read_exr(path)); },
        py::arg("path"),
        "Reads an OpenEXR file into a tirpol.Image: channel name → float32 array (H, W), header "
        "attributes in "
        ".attributes. Raises tirpol.Error naming the file if it is missing, truncated or corrupt.");
    m.def(
        "write_exr",
        [](const std::filesystem::path& path, const py::object& channels,
           const py::object& attributes) {
            const py::object attrs = attributes.is_none() && py::hasattr(channels, "attributes")
                                         ? channels.attr("attributes")
                                         : attributes;
            Image image = from_python(channels, attrs);
            py::gil_scoped_release release;
            write_exr(path, image);
        },
        py::arg("path"), py::arg("image"), py::arg("attributes") = py::none(),
        "Writes channels (a mapping name → 2-D array, all the same shape; stored as 32-bit float, "
        "so float32 data "
        "round-trips exactly) and header attributes (int, float, str or a sequence of floats; "
        "default: "
        "image.attributes when `image` is a tirpol.Image) atomically to an OpenEXR file.");
}

}  // namespace

void bind_core(py::module_& m) {
    bind_stokes(m);
    bind_mueller(m);
    bind_radiometry(m);
    bind_exr(m);
}

}  // namespace tirpol::python
