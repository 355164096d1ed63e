#include <charconv>
#include <cmath>
#include <vector>

#include "tirpol/calibration/analyzer.h"
#include "tirpol/calibration/microgrid_stokes.h"
#include "tirpol/core/error.h"
#include "tirpol/core/stokes.h"

namespace tirpol::calibration {

namespace {
// Four equally spaced angles give cond(W) = √2; 0/30/60/90 about 1.7. A set whose rows nearly
// coincide in (cos 2θ, sin 2θ), e.g. 0/1/2/3°, amplifies noise by orders of magnitude: refuse it.
constexpr double kMaxConditionNumber = 10.0;

std::string angles_text(const std::array<double, 4>& a) {
    return fmt::format("{:g},{:g},{:g},{:g}", a[0], a[1], a[2], a[3]);
}
}  // namespace

MicrogridPattern::MicrogridPattern(const std::array<double, 4>& angles_deg,
                                   std::string_view context)
    : m_angles_deg(angles_deg) {
    for (std::size_t i = 0; i < 4; ++i) {
        const double a = angles_deg[i];
        if (!std::isfinite(a) || a < 0.0 || a >= 180.0)
            fail("{}: angle at cell ({},{}) is {:g}°; expected a finite angle in [0°, 180°)",
                 context, i / 2, i % 2, a);
        for (std::size_t j = 0; j < i; ++j)
            if (same_polarizer_angle(a, angles_deg[j]))
                fail(
                    "{}: angle {:g}° appears at cells ({},{}) and ({},{}); expected four distinct "
                    "analyzer angles",
                    context, a, j / 2, j % 2, i / 2, i % 2);
    }
    const AnalyzerModel ideal = AnalyzerModel::ideal({angles_deg.begin(), angles_deg.end()});
    const double condition = ideal.condition_number();
    if (!(condition <= kMaxConditionNumber))
        fail(
            "{}: angles {} do not determine S1 and S2 (condition number {:.3g} of the ideal "
            "measurement matrix; "
            "expected ≤ {:g}, e.g. 0/45/90/135°)",
            context, angles_text(angles_deg), condition, kMaxConditionNumber);
}

MicrogridPattern MicrogridPattern::sony_imx250mzr() {
    return MicrogridPattern({90.0, 45.0, 135.0, 0.0});
}

MicrogridPattern MicrogridPattern::parse(std::string_view text, std::string_view context) {
    if (text == "sony" || text == "imx250mzr") return sony_imx250mzr();
    std::array<double, 4> angles{};
    std::size_t count = 0;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t comma = std::min(text.find(',', start), text.size());
        std::string_view field = text.substr(start, comma - start);
        while (!field.empty() && field.front() == ' ') field.remove_prefix(1);
        while (!field.empty() && field.back() == ' ') field.remove_suffix(1);
        double value = 0.0;
        const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
        if (field.empty() || ec != std::errc() || end != field.data() + field.size() || count >= 4)
            fail(
                "{}: '{}' is not a microgrid pattern; expected four angles in degrees for cells "
                "(0,0),(0,1),(1,0),(1,1) "
                "such as \"90,45,135,0\", or \"sony\"",
                context, text);
        angles[count++] = value;
        start = comma + 1;
    }
    if (count != 4)
        fail(
            "{}: '{}' has {} angle(s); expected four, for cells (0,0),(0,1),(1,0),(1,1) (e.g. "
            "\"90,45,135,0\")",
            context, text, count);
    return MicrogridPattern(angles, context);
}

MicrogridPattern MicrogridPattern::from_attributes(const Attributes& attributes) {
    const auto it = attributes.find("microgrid_pattern_deg");
    if (it == attributes.end())
        fail(
            "image header: attribute 'microgrid_pattern_deg' is missing; expected the four "
            "analyzer angles of the "
            "microgrid cell");
    const auto* values = std::get_if<std::vector<double>>(&it->second);
    if (!values || values->size() != 4)
        fail(
            "image header: attribute 'microgrid_pattern_deg' must be a list of four angles in "
            "degrees");
    return MicrogridPattern({(*values)[0], (*values)[1], (*values)[2], (*values)[3]},
                            "image header attribute 'microgrid_pattern_deg'");
}

int MicrogridPattern::cell_of(double angle_deg) const {
    for (int i = 0; i < 4; ++i)
        if (same_polarizer_angle(m_angles_deg[static_cast<std::size_t>(i)], angle_deg)) return i;
    fail("microgrid pattern {} has no analyzer at {:g}°", text(), angle_deg);
}

std::string MicrogridPattern::text() const { return angles_text(m_angles_deg); }

void MicrogridPattern::write_to(Attributes& attributes) const {
    attributes["microgrid_pattern"] = text();
    attributes["microgrid_pattern_deg"] =
        std::vector<double>(m_angles_deg.begin(), m_angles_deg.end());
}

}  // namespace tirpol::calibration
