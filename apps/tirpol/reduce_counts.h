#pragma once
// `tirpol reduce SESSION -o OUT` without --calibration: the counts quick look
// (calibration/counts_quicklook.h), written and printed with its label.

#include <string>

namespace tirpol::cli {

/// What `tirpol reduce` passes on when no --calibration is given.
struct CountsQuicklookArgs {
    std::string session, output, quicklooks;
    double max_saturated_fraction = 0.01;
    bool force = false;
};

void run_reduce_counts(const CountsQuicklookArgs& args);

}  // namespace tirpol::cli
