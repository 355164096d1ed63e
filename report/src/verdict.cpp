#include "tirpol/report/verdict.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace tirpol::report {

namespace {
std::string dof_text(double dof) { return std::isfinite(dof) ? fmt::format("{:.0f}", dof) : "∞"; }
}  // namespace

Agreement worse(Agreement a, Agreement b) {
    return static_cast<int>(a) >= static_cast<int>(b) ? a : b;
}

std::string to_string(Agreement agreement) {
    switch (agreement) {
        case Agreement::NoData:
            return "no data";
        case Agreement::ConsistentWithNoise:
            return "consistent with noise";
        case Agreement::ExceedsNoise:
            return "exceeds noise";
    }
    return "?";
}

std::string to_string(SigmaCheck check) {
    switch (check) {
        case SigmaCheck::NoData:
            return "no data";
        case SigmaCheck::Plausible:
            return "σ plausible";
        case SigmaCheck::Overestimated:
            return "σ overestimated";
        case SigmaCheck::Underestimated:
            return "σ underestimated";
    }
    return "?";
}

std::string explain(const MeanDifferenceTest& t) {
    if (t.verdict == Agreement::NoData) return "no pixel where both images have data";
    return fmt::format(
        "mean difference {:.4g} ± {:.2g} (t = {:.2f}, ν = {}, p = {:.2g}); detectable bias {:.2g} "
        "at "
        "{:.1f} % false alarm, {:.0f} % power",
        t.difference, t.combined.sigma, t.t, dof_text(t.combined.dof), t.p_value, t.detectable_bias,
        100.0 * t.false_alarm, 100.0 * t.power);
}

std::string explain(const SigmaDiagnostic& d) {
    switch (d.verdict) {
        case SigmaCheck::NoData:
            return "too few pixels for a σ diagnostic";
        case SigmaCheck::Plausible:
            return fmt::format("z scatters with σ {:.2f} (expected 1; variance {:.2f} ± {:.2f})",
                               d.sigma_factor, d.z_variance, d.z_variance_sigma);
        case SigmaCheck::Overestimated:
            return fmt::format(
                "z scatters with σ {:.2f} (expected 1; variance {:.2f} ± {:.2f}): the stated "
                "per-pixel "
                "σ is about {:.1f}× too large",
                d.sigma_factor, d.z_variance, d.z_variance_sigma,
                1.0 / std::max(d.sigma_factor, 1e-6));
        case SigmaCheck::Underestimated:
            return fmt::format(
                "z scatters with σ {:.2f} (expected 1; variance {:.2f} ± {:.2f}): the stated "
                "per-pixel "
                "σ is about {:.1f}× too small, or the difference varies within the region",
                d.sigma_factor, d.z_variance, d.z_variance_sigma, d.sigma_factor);
    }
    return "";
}

}  // namespace tirpol::report
