#pragma once
/// \file summary_text.h
/// The report's answer in one paragraph: which regions agree with the simulation within the noise,
/// which do not and in which quantity by how much, whether the measurement was calibrated over the
/// scene's radiances, what each part of a region mean's σ contains (measurement, render,
/// registration), and whether the verdicts have power (the smallest bias the tests detect, against
/// the simulated signal they test).

#include <string>

#include "tirpol/report/comparison_report.h"

namespace tirpol::report {

/// Whether the region-mean test of `quantity` (S0, S1 or S2) in `region` has power: its detectable
/// bias is smaller than the magnitude of the simulated region mean it tests. Without power a
/// simulation that predicted zero would read "consistent with noise" as well, so "consistent" says
/// little. False for a quantity without data, and for DoLP, which has no test.
bool verdict_has_power(const RegionResult& region, Quantity quantity);

/// Plain UTF-8 text (no markup), one paragraph of a few sentences; read from `result` only.
std::string summary_paragraph(const CompareResult& result);

/// What `tirpol compare` prints: the registration and its residual, the summary paragraph, one
/// table row per region (pixels, S0 bias in kelvin, each quantity's t of the means with its
/// detectable bias and verdict; columns padded by displayed width), the notes and the report path.
std::string comparison_text(const CompareResult& result);

}  // namespace tirpol::report
