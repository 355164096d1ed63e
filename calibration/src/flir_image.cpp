#include "tirpol/calibration/flir_image.h"

#include <fmt/printf.h>

#include <cmath>

#include "tirpol/core/exr_io.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::calibration {

FlirImageResult flir_temperature_image(const FlirImageOptions& o) {
    const FlirPlanck& p = o.planck;
    const FlirConditions& c = o.conditions;
    OutputGuard().input(o.image, "RAW_IMAGE").output_file(o.output, "--output").check(o.force);
    validate_flir(p, c);
    const Image raw = read_raw_image(o.image, "counts", o.channel);
    Image out(raw.width(), raw.height());
    auto& t = out.add_channel("temperature_k");
    const auto& counts = raw.channel("counts");
    FlirImageResult result;
    for (std::size_t i = 0; i < counts.size(); ++i) {
        t[i] = static_cast<float>(flir_temperature_from_raw(p, counts[i], c));
        if (!std::isfinite(t[i])) ++result.pixels_without_solution;
    }
    auto& at = out.attributes();
    at["units_temperature_k"] = std::string("K");
    at["planck_r1_r2_b_f_o"] = std::vector<double>{p.r1, p.r2, p.b, p.f, p.o};
    at["emissivity"] = c.emissivity;
    at["distance_m"] = c.distance_m;
    at["reflected_k"] = c.reflected_k;
    at["atmosphere_k"] = c.atmosphere_k;
    at["humidity_pct"] = c.humidity_pct;
    at["window_k"] = c.window_k;
    at["window_transmission"] = c.window_transmission;
    at["atmospheric_transmission_half_path"] =
        flir_atmospheric_transmission(c.distance_m / 2.0, c.atmosphere_k, c.humidity_pct);
    at["source"] = o.image;
    write_exr(o.output, out);
    result.output = o.output;
    result.temperature_k = channel_stats(t);
    return result;
}

std::string flir_image_text(const FlirImageResult& r) {
    const ChannelStats& s = r.temperature_k;
    return fmt::sprintf(
        "object temperature: min %.2f °C, mean %.2f °C, max %.2f °C (%zu pixel(s) without a "
        "solution) → %s\n",
        s.min - kZeroCelsiusK, s.mean - kZeroCelsiusK, s.max - kZeroCelsiusK,
        r.pixels_without_solution, r.output);
}

}  // namespace tirpol::calibration
