// The radiometric calibration EXR (docs/calibration.md, "Calibration file").

#include <fmt/format.h>

#include "tirpol/calibration/radiometric.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"

namespace tirpol::calibration {

namespace {
constexpr const char* kKind = "radiometric";
// 1: one camera state (no format_version attribute); 2: adds the FPA-temperature dependence.
constexpr int kFormatVersion = 2;

std::string fpa_channel(const char* plane, int power) {
    return fmt::format("{}_fpa{}", plane, power);
}

template <typename T>
const T& attribute(const Image& image, const std::string& path, const std::string& name) {
    const auto it = image.attributes().find(name);
    if (it == image.attributes().end())
        fail("{}: missing attribute '{}' of a radiometric calibration", path, name);
    const T* value = std::get_if<T>(&it->second);
    if (!value) fail("{}: attribute '{}' has the wrong type", path, name);
    return *value;
}
}  // namespace

void write_radiometric_calibration(const std::string& path, const RadiometricCalibration& cal) {
    Image image(cal.width, cal.height);
    image.set_channel("gain", cal.gain);
    image.set_channel("offset", cal.offset);
    if (!cal.quadratic.empty()) image.set_channel("quadratic", cal.quadratic);
    image.set_channel("bad", cal.bad);
    image.set_channel("residual_rms", cal.residual_rms);
    image.set_channel("fit_quality", cal.fit_quality);
    for (int e = 1; e <= cal.fpa_degree(); ++e) {
        image.set_channel(fpa_channel("offset", e),
                          cal.offset_fpa[static_cast<std::size_t>(e - 1)]);
        image.set_channel(fpa_channel("gain", e), cal.gain_fpa[static_cast<std::size_t>(e - 1)]);
    }
    auto& a = image.attributes();
    a["tirpol_calibration"] = std::string(kKind);
    a["format_version"] = kFormatVersion;
    a["fpa_degree"] = cal.fpa_degree();
    if (cal.fpa_degree() > 0) {
        a["fpa_model"] = std::string(
            "gain, offset polynomial in (T_fpa - fpa_reference_k); Nugent, Shaw & Pust 2013");
        a["fpa_reference_k"] = cal.fpa_reference_k;
        a["fpa_min_k"] = cal.fpa_min_k;  // doubles: an EXR float vector would round them
        a["fpa_max_k"] = cal.fpa_max_k;
        a["fpa_temperatures_k"] = cal.fpa_temperatures_k;
        a["units_offset_fpa"] = std::string("counts/K^a (a = the channel's suffix)");
        a["units_gain_fpa"] = std::string("counts/(W/(m^2 sr))/K^a");
    }
    a["model"] = std::string(cal.quadratic.empty() ? "linear" : "quadratic");
    a["temperatures_k"] = cal.temperatures_k;
    a["radiances_w_m2_sr"] = cal.radiances_w_m2_sr;
    a["band_um"] = std::vector<double>{cal.band_lo_um, cal.band_hi_um};
    a["rsr_wavelength_um"] = cal.rsr_wavelength_um;
    a["rsr_response"] = cal.rsr_response;
    a["camera_id"] = cal.camera_id;
    a["camera_vendor"] = cal.camera.vendor;
    a["camera_model"] = cal.camera.model;
    a["camera_serial"] = cal.camera.serial;
    a["camera_pixel_format"] = cal.camera.pixel_format;
    a["camera_bits_per_pixel"] = cal.camera.bits_per_pixel;
    a["created_utc"] = cal.created_utc;
    a["units_gain"] = std::string("counts/(W/(m^2 sr))");
    a["units_offset"] = std::string("counts");
    a["units_quadratic"] = std::string("counts/(W/(m^2 sr))^2");
    a["units_residual_rms"] = std::string("counts");
    a["bad_bits"] = std::string("1 dead, 2 hot, 4 noisy, 8 non-linear, 16 saturated");
    a["bad_dead"] = static_cast<int>(cal.bad_count(kDead));
    a["bad_hot"] = static_cast<int>(cal.bad_count(kHot));
    a["bad_noisy"] = static_cast<int>(cal.bad_count(kNoisy));
    a["bad_nonlinear"] = static_cast<int>(cal.bad_count(kNonLinear));
    a["bad_saturated"] = static_cast<int>(cal.bad_count(kSaturated));
    write_exr(path, image);
}

RadiometricCalibration read_radiometric_calibration(const std::string& path) {
    const Image image = read_exr(path);
    const auto& kind = attribute<std::string>(image, path, "tirpol_calibration");
    if (kind != kKind) fail("{}: tirpol_calibration = '{}'; expected '{}'", path, kind, kKind);
    int version = 1;
    if (image.attributes().count("format_version"))
        version = attribute<int>(image, path, "format_version");
    if (version < 1 || version > kFormatVersion)
        fail(
            "{}: format_version = {}; this tirpol reads radiometric calibrations of version 1 to "
            "{} (written by a "
            "newer tirpol?)",
            path, version, kFormatVersion);
    RadiometricCalibration cal;
    cal.width = image.width();
    cal.height = image.height();
    cal.gain = image.channel("gain");
    cal.offset = image.channel("offset");
    if (image.has_channel("quadratic")) cal.quadratic = image.channel("quadratic");
    cal.bad = image.channel("bad");
    cal.residual_rms = image.channel("residual_rms");
    cal.fit_quality = image.channel("fit_quality");
    cal.temperatures_k = attribute<std::vector<double>>(image, path, "temperatures_k");
    cal.radiances_w_m2_sr = attribute<std::vector<double>>(image, path, "radiances_w_m2_sr");
    const auto& band = attribute<std::vector<double>>(image, path, "band_um");
    if (band.size() != 2 || !(band[0] < band[1]))
        fail("{}: band_um must be [lo, hi] with lo < hi", path);
    cal.band_lo_um = band[0];
    cal.band_hi_um = band[1];
    cal.rsr_wavelength_um = attribute<std::vector<double>>(image, path, "rsr_wavelength_um");
    cal.rsr_response = attribute<std::vector<double>>(image, path, "rsr_response");
    cal.camera_id = attribute<std::string>(image, path, "camera_id");
    // The camera_* attributes are absent from calibrations written before they existed.
    if (image.attributes().count("camera_serial")) {
        cal.camera.vendor = attribute<std::string>(image, path, "camera_vendor");
        cal.camera.model = attribute<std::string>(image, path, "camera_model");
        cal.camera.serial = attribute<std::string>(image, path, "camera_serial");
        cal.camera.pixel_format = attribute<std::string>(image, path, "camera_pixel_format");
        cal.camera.bits_per_pixel = attribute<int>(image, path, "camera_bits_per_pixel");
    }
    cal.created_utc = attribute<std::string>(image, path, "created_utc");
    const int degree = version >= 2 ? attribute<int>(image, path, "fpa_degree") : 0;
    if (degree < 0 || degree > 2) fail("{}: fpa_degree = {}; expected 0, 1 or 2", path, degree);
    if (degree > 0) {
        cal.fpa_reference_k = attribute<double>(image, path, "fpa_reference_k");
        cal.fpa_min_k = attribute<double>(image, path, "fpa_min_k");
        cal.fpa_max_k = attribute<double>(image, path, "fpa_max_k");
        if (!(cal.fpa_min_k <= cal.fpa_max_k) || !(cal.fpa_reference_k > 0.0))
            fail("{}: expected fpa_min_k ≤ fpa_max_k and fpa_reference_k above 0 K", path);
        cal.fpa_temperatures_k = attribute<std::vector<double>>(image, path, "fpa_temperatures_k");
    }
    for (int e = 1; e <= degree; ++e)
        for (const char* plane : {"offset", "gain"}) {
            const std::string name = fpa_channel(plane, e);
            if (!image.has_channel(name))
                fail("{}: missing channel '{}' of an FPA-dependent calibration (fpa_degree {})",
                     path, name, degree);
            (plane[0] == 'o' ? cal.offset_fpa : cal.gain_fpa).push_back(image.channel(name));
        }
    return cal;
}

}  // namespace tirpol::calibration
