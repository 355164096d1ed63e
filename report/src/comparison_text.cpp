#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "tirpol/report/comparison_report.h"

namespace tirpol::report {

std::string comparison_text(const CompareResult& r) {
    const auto& g = r.registration;
    std::string text =
        fmt::format("registration: {} ({}), residual misalignment {:.3f} px\n", to_string(g.method),
                    g.model, std::hypot(g.residual_shift_px[0], g.residual_shift_px[1]));
    if (!g.note.empty()) text += "  " + g.note + "\n";
    text += summary_paragraph(r) + "\n";
    // fmt pads by displayed width (σ and ± are one column, two bytes); the name column fits the
    // longest name.
    std::size_t name_width = 16;
    for (const auto& region : r.regions) name_width = std::max(name_width, region.name.size());
    text += fmt::format("{:<{}} {:>7} {:>14} {:<26} {:<26} {:<26} {}\n", "region", name_width,
                        "pixels", "S0 bias [K]", "S0 diff/σ_mean (detect)",
                        "S1 diff/σ_mean (detect)", "S2 diff/σ_mean (detect)", "verdict");
    for (const auto& region : r.regions) {
        const auto& k = region.s0_bias_k;
        const std::string kelvin =
            k ? fmt::format("{:.3f}±{:.3f}", k->bias_k, k->bias_sigma_k) : "–";
        text +=
            fmt::format("{:<{}} {:>7} {:>14}", region.name, name_width, region.pixel_count, kelvin);
        for (const Quantity q : kZQuantities) {
            const auto& v = region.verdicts[q];
            text += fmt::format(
                " {:<26}", fmt::format("{:+.1f} ({:.2g}) {}{}", v.mean.t, v.mean.detectable_bias,
                                       v.mean.verdict == Agreement::ExceedsNoise ? "EXCEEDS" : "ok",
                                       v.sigma.verdict == SigmaCheck::Overestimated    ? " σ-high"
                                       : v.sigma.verdict == SigmaCheck::Underestimated ? " σ-low"
                                                                                       : ""));
        }
        text += fmt::format(" {}\n", to_string(region.verdict));
    }
    for (const auto& note : r.notes) text += "note: " + note + "\n";
    return text + "report: " + r.html.string() + "\n";
}

}  // namespace tirpol::report
