#pragma once
// Turning a thermal frame (counts of an uncooled bolometer: a few counts of target contrast on a
// pedestal of thousands, vignetting and gradients larger than the target, column offsets, stuck
// pixels) into the 8-bit image OpenCV's target detectors expect.

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace tirpol::calibration::detail {

/// A plane as a CV_32F image, non-finite values replaced by the median of the finite ones.
/// Empty with `failure` set when fewer than half of the values are finite.
cv::Mat finite_image(const std::vector<float>& plane, int width, int height, std::string& failure);

/// Replaces stuck (dead) pixels by the median of their 3×3 neighbourhood: those that differ from
/// it by more than the frame's whole robust range (0.5th–99.5th percentile), which no pixel of the
/// scene does, however sharp the target's edges.
void replace_stuck_pixels(cv::Mat& image);

/// Removes fixed-pattern column offsets: each column's median of the horizontally high-passed
/// image (the frame minus its 15-pixel running mean along rows). A checkerboard's vertical edges
/// alternate in sign down a column, so they do not bias the median.
void remove_column_offsets(cv::Mat& image);

/// Subtracts the large-scale background (a Gaussian of sigma = 1/20 of the frame's larger side,
/// at least 32 px):
/// vignetting, narcissus and gradients across the frame, which can be ten times the target's
/// contrast, so that the stretch to 8 bits spends its levels on the target.
void subtract_background(cv::Mat& image);

/// Linear stretch to 8 bits between the 0.5th and 99.5th percentiles: a few hot or cold pixels do
/// not set the range (as min/max would), and a target of a few counts spans most of 0–255 (a
/// 14- to 8-bit shift would leave it within 1–3 grey levels). Empty when the frame is flat.
cv::Mat stretch_to_8bit(const cv::Mat& image);

}  // namespace tirpol::calibration::detail
