#include <fmt/format.h>

#include <algorithm>

#include "tirpol/core/stokes.h"

namespace tirpol {

std::string polarizer_angle_tag(double angle_deg) {
    std::string tag = fmt::format("{:g}", polarizer_angle_deg(polarizer_angle_key(angle_deg)));
    std::replace(tag.begin(), tag.end(), '.', 'p');
    return tag;
}

}  // namespace tirpol
