#include <fmt/printf.h>

#include <variant>

#include "tirpol/calibration/radiometric.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/output_guard.h"

namespace tirpol::calibration {

namespace {
/// The FPA temperature given, else the one a session frame's header carries.
std::optional<double> frame_fpa_temperature_k(const Image& raw, const std::string& path,
                                              std::optional<double> given) {
    if (given) return given;
    return read_stokes_image_header(raw, path).fpa_temperature_k;
}
}  // namespace

TemperatureImageResult brightness_temperature_image(const TemperatureImageOptions& o) {
    OutputGuard()
        .input(o.image, "IMAGE")
        .input(o.calibration, "--calibration")
        .output_file(o.output, "--output")
        .check(o.force);
    const auto cal = read_radiometric_calibration(o.calibration);
    const Image raw = read_raw_image(o.image, "counts", o.channel);
    if (raw.width() != cal.width || raw.height() != cal.height)
        fail("{}: image is {}×{} but calibration {} is {}×{}", o.image, raw.width(), raw.height(),
             o.calibration, cal.width, cal.height);
    const auto fpa_k = frame_fpa_temperature_k(raw, o.image, o.fpa_temperature_k);
    const auto radiance = counts_to_radiance(cal, raw.channel("counts"), fpa_k);
    TemperatureImageResult result;
    result.output = o.output;
    result.warning = extrapolation_warning(cal, radiance, fpa_k);
    Image out(raw.width(), raw.height());
    out.set_channel("radiance", radiance);
    out.set_channel("temperature_k", brightness_temperature(cal.band(), radiance));
    result.temperature_k = channel_stats(out.channel("temperature_k"));
    if (result.temperature_k.finite_count == 0)
        fail(
            "{}: no pixel gives a finite brightness temperature with calibration {} (counts below "
            "its offsets "
            "everywhere: another camera, bit depth or gain setting?); nothing written",
            o.image, o.calibration);
    out.attributes()["units_radiance"] = std::string("W/(m^2 sr)");
    out.attributes()["units_temperature_k"] = std::string("K");
    write_stokes_image_header(out, {.band_um = std::array{cal.band_lo_um, cal.band_hi_um}});
    out.attributes()["calibration"] = o.calibration;
    out.attributes()["source"] = o.image;
    if (result.warning) out.attributes()["calibration_warning"] = *result.warning;
    write_exr(o.output, out);
    return result;
}

std::string temperature_image_text(const TemperatureImageResult& r) {
    std::string text = r.warning ? fmt::sprintf("warning: %s\n", *r.warning) : "";
    return text + fmt::sprintf("brightness temperature: min %.2f K, mean %.2f K, max %.2f K → %s\n",
                               r.temperature_k.min, r.temperature_k.mean, r.temperature_k.max,
                               r.output);
}

}  // namespace tirpol::calibration
