#pragma once
/// \file fit_plot.h
/// A plot like the paper's Fig. 1: measured ε_S0(θ) and ε_S1(θ) with 2σ error bars and the fitted
/// model curves, one panel each, one colour per dataset/band; axes, ticks, labels and a legend.
/// Drawn with OpenCV directly rather than core's write_line_plot, which has neither error bars nor
/// stacked panels; the tick positions are core's nice_ticks.

#include <filesystem>
#include <string>
#include <vector>

#include "tirpol/fitting/emissivity_data.h"
#include "tirpol/fitting/microfacet_fit.h"

namespace tirpol::fitting {

/// Writes the PNG (atomically). The curves are the fit's own quadrature at 0.5° steps.
void write_fit_plot(const std::filesystem::path& png,
                    const std::vector<EmissivityDataset>& datasets,
                    const MicrofacetFitResult& result, const std::string& title,
                    const QuadratureOptions& quadrature = {});

}  // namespace tirpol::fitting
