#include <cmath>
#include <string>

#include "camera/pixel_formats.h"
#include "tirpol/acquisition/camera.h"
#include "tirpol/core/error.h"

namespace tirpol::acquisition {

std::array<double, 4> parse_microgrid_pattern_deg(std::string_view text, std::string_view context) {
    if (text == "sony" || text == "imx250mzr") return kSonyPolarizedLayoutDeg;
    std::array<double, 4> angles{};
    std::size_t start = 0;
    for (std::size_t i = 0; i < 4; ++i) {
        const std::size_t comma = text.find(',', start);
        const bool last = i == 3;
        if (last != (comma == std::string_view::npos))
            fail("{}: '{}': expected \"sony\" or four comma-separated angles in degrees", context,
                 text);
        const std::string item(text.substr(start, last ? std::string_view::npos : comma - start));
        std::size_t used = 0;
        double value = 0.0;
        try {
            value = std::stod(item, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (item.empty() || used != item.size() || !std::isfinite(value) || value < 0.0 ||
            value >= 180.0)
            fail("{}: '{}': angle {} is '{}' (expected a number in [0, 180) degrees)", context,
                 text, i + 1, item);
        for (std::size_t k = 0; k < i; ++k)
            if (angles[k] == value)
                fail("{}: '{}': angle {} repeats angle {} (expected four distinct angles)", context,
                     text, i + 1, k + 1);
        angles[i] = value;
        start = comma + 1;
    }
    return angles;
}

}  // namespace tirpol::acquisition
