#pragma once
/// \file verdict.h
/// The verdict on one quantity's z statistic: do the measured − simulated differences exceed the
/// stated noise, and is the stated noise itself plausible? A pooled verdict over S0, S1, S2 can hide a
/// quantity that alone exceeds the noise, so verdicts are per quantity; a region's verdict is the
/// worst of its quantities.

#include <string>

#include "tirpol/report/statistics.h"

namespace tirpol::report {

/// RMS z below this with the fraction test passed: σ is overestimated (z ~ N(0, 1) has RMS 1).
inline constexpr double kRmsLow = 0.7;
/// RMS z above this: the differences or σ are wrong even if few pixels pass |z| > 2 (heavy tails).
inline constexpr double kRmsHigh = 1.5;

enum class ZVerdict {
    NoData,              ///< no pixel with a valid z
    Consistent,          ///< |z| > 2 fraction as expected from noise and RMS z compatible with 1
    SigmaOverestimated,  ///< fraction fine but RMS z < kRmsLow: the stated σ is too large, the test is blunt
    ExceedsNoise,        ///< |z| > 2 fraction beyond noise, or RMS z > kRmsHigh
};

/// Classifies `z`. The RMS thresholds apply only when they are also more than three standard
/// errors of the RMS (1/√(2n) for n normal values) away from 1, so a handful of pixels never flags.
ZVerdict z_verdict(const ZStats& z);

/// The worse of two verdicts (ExceedsNoise > SigmaOverestimated > Consistent > NoData).
ZVerdict worse(ZVerdict a, ZVerdict b);

/// "no data", "consistent with noise", "σ overestimated", "exceeds noise".
std::string to_string(ZVerdict verdict);

/// One sentence explaining `verdict` for `z` (e.g. "RMS z = 0.45: the stated σ is about 2.2× too large").
std::string explain(ZVerdict verdict, const ZStats& z);

}  // namespace tirpol::report
