#pragma once
/// \file verdict.h
/// A region's verdict on one quantity, in two separate parts: the agreement (is the region-mean
/// difference within the noise of both sides, with the bias the test could have detected) and the
/// σ diagnostic (is the stated per-pixel σ plausible, from the scatter of z). A region's agreement
/// is "exceeds noise" when any of S0, S1, S2 exceeds it; each quantity is tested at the Šidák level
/// that keeps the region's false-alarm rate at the design's.

#include <string>

#include "tirpol/report/mean_difference_test.h"

namespace tirpol::report {

/// The verdict of one quantity in one region.
struct QuantityVerdict {
    MeanDifferenceTest mean;  ///< the agreement test of the region mean
    SigmaDiagnostic sigma;    ///< the plausibility of the per-pixel σ
};

/// The worse of two agreements (ExceedsNoise > ConsistentWithNoise > NoData).
Agreement worse(Agreement a, Agreement b);

/// "no data", "consistent with noise", "exceeds noise".
std::string to_string(Agreement agreement);

/// "no data", "σ plausible", "σ overestimated", "σ underestimated".
std::string to_string(SigmaCheck check);

/// One sentence on the agreement, e.g. "mean difference −0.012 ± 0.004 (t = −3.0, ν = 812, p =
/// 0.003; detectable bias 0.013 at 1.7 % false alarm, 80 % power)".
std::string explain(const MeanDifferenceTest& test);

/// One sentence on the σ diagnostic, e.g. "z scatters with σ 0.45 (expected 1 ± 0.05): the stated σ
/// is about 2.2× too large".
std::string explain(const SigmaDiagnostic& diagnostic);

}  // namespace tirpol::report
