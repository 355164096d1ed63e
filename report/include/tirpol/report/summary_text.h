#pragma once
/// \file summary_text.h
/// The report's answer in one paragraph: which regions agree with the simulation within the noise,
/// which do not and in which quantity by how much, whether the measurement was calibrated over the
/// scene's radiances, what each side's σ contains, and how large a bias the tests could detect.

#include <string>

#include "tirpol/report/comparison_report.h"

namespace tirpol::report {

/// Plain UTF-8 text (no markup), a few sentences; read from `result` only.
std::string summary_paragraph(const CompareResult& result);

}  // namespace tirpol::report
