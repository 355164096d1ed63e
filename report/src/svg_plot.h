#pragma once
// Line-art figures of the report (scatter plots, histograms) as inline SVG: text stays text, so any
// Unicode region name or unit renders in the browser's font, scales without blur and can be copied.
// Axes carry "nice" tick values (1, 2, 2.5 or 5 × 10^k). Private to the report module.

#include <string>
#include <vector>

#include "figures.h"

namespace tirpol::report::detail {

/// Tick values covering [lo, hi] with a step of 1, 2, 2.5 or 5 × 10^k chosen so that about `target`
/// ticks fall inside (Heckbert, "Nice numbers for graph labels", Graphics Gems, 1990). Only ticks
/// within [lo, hi] (to a relative 1e-9) are returned; lo < hi.
std::vector<double> nice_ticks(double lo, double hi, int target = 5);

/// `value` printed with just the digits `step` needs ("0.25", "30", "1e-05"; "0" for |value| ≪
/// step).
std::string tick_label(double value, double step);

/// Simulated (y) against measured (x), one colour per series, dashed 1:1 line; legend below the
/// plot.
std::string svg_scatter(const std::string& title, const std::string& units,
                        const std::vector<ScatterSeries>& series);

/// Density histogram of `values` over [lo, hi] with grey vertical markers and, when gaussian_sigma
/// > 0, the N(gaussian_mean, gaussian_sigma²) density as a red curve.
std::string svg_histogram(const std::string& title, const std::string& x_label,
                          const std::vector<float>& values, double lo, double hi,
                          const std::vector<double>& markers, double gaussian_mean,
                          double gaussian_sigma);

/// The region overview: its PNG as an embedded image and each region's name as SVG text on top, in
/// the region's colour with a white halo, so any Unicode name renders in the browser's font.
std::string svg_region_overview(const RegionOverview& overview);

}  // namespace tirpol::report::detail
