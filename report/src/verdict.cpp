#include "tirpol/report/verdict.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace tirpol::report {

ZVerdict z_verdict(const ZStats& z) {
    if (z.pixel_count == 0) return ZVerdict::NoData;
    const double rms_se = 1.0 / std::sqrt(2.0 * static_cast<double>(z.pixel_count));
    if (!consistent_with_noise(z) || (z.rms > kRmsHigh && z.rms - 3.0 * rms_se > 1.0)) return ZVerdict::ExceedsNoise;
    if (z.rms < kRmsLow && z.rms + 3.0 * rms_se < 1.0) return ZVerdict::SigmaOverestimated;
    return ZVerdict::Consistent;
}

ZVerdict worse(ZVerdict a, ZVerdict b) { return static_cast<int>(a) >= static_cast<int>(b) ? a : b; }

std::string to_string(ZVerdict verdict) {
    switch (verdict) {
        case ZVerdict::NoData: return "no data";
        case ZVerdict::Consistent: return "consistent with noise";
        case ZVerdict::SigmaOverestimated: return "σ overestimated";
        case ZVerdict::ExceedsNoise: return "exceeds noise";
    }
    return "?";
}

std::string explain(ZVerdict verdict, const ZStats& z) {
    switch (verdict) {
        case ZVerdict::NoData: return "no pixel has a finite z";
        case ZVerdict::Consistent:
            return fmt::format("|z| > 2 in {:.2f} % (noise alone: 4.55 %), RMS z = {:.2f}", 100.0 * z.fraction_above_2,
                               z.rms);
        case ZVerdict::SigmaOverestimated:
            return fmt::format("RMS z = {:.2f} (expected 1): the stated σ is about {:.1f}× too large, so this test "
                               "cannot detect differences smaller than that",
                               z.rms, 1.0 / std::max(z.rms, 1e-6));
        case ZVerdict::ExceedsNoise:
            return z.rms > kRmsHigh
                       ? fmt::format("|z| > 2 in {:.2f} % (noise alone: 4.55 %), RMS z = {:.2f} ≫ 1",
                                     100.0 * z.fraction_above_2, z.rms)
                       : fmt::format("|z| > 2 in {:.2f} % (noise alone: 4.55 %), RMS z = {:.2f}",
                                     100.0 * z.fraction_above_2, z.rms);
    }
    return "";
}

}  // namespace tirpol::report
