#pragma once
/// \file region_statistics.h
/// What the page reads out over a rectangle the operator dragged: the mean and spread of each
/// channel, the angle of polarization as the axial quantity it is, and a focus metric to turn the
/// lens by. Computed here on the server's floating-point images, not in the page's JavaScript, so
/// that they are tested without a browser.

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>

#include "display_frame.h"

namespace tirpol::live {

/// A rectangle of pixels, corners included (x0 ≤ x1, y0 ≤ y1).
struct PixelRegion {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

/// Mean and sample standard deviation of the values that count (finite, unflagged, unmasked).
struct ChannelStatistics {
    std::size_t count = 0;
    double mean = 0.0;  ///< NaN when count is 0
    double std = 0.0;   ///< NaN when count < 2
};

/// `region` clipped to a width × height image; nullopt when nothing of it lies inside. Throws
/// tirpol::Error when the corners are out of order.
std::optional<PixelRegion> clip_region(const PixelRegion& region, int width, int height);

/// Linear mean ± standard deviation of `channel` over `region` (already clipped), leaving out
/// flagged and non-finite pixels and those where `keep` (if non-null) is false.
ChannelStatistics linear_statistics(const DisplayChannel& channel, int width,
                                    const PixelRegion& region,
                                    const std::vector<bool>* keep = nullptr);

/// Axial statistics of an angle in degrees (AoP: θ and θ + 180° are the same state), after Mardia
/// & Jupp, Directional Statistics (2000) §9.3.2: the mean is half the mean direction of 2θ, in
/// [0, 180); the spread is the circular standard deviation √(−2 ln R̄) of 2θ, halved, in degrees.
/// A linear mean of 1° and 179° says 90°; this says 0° with a spread of 1°.
ChannelStatistics axial_statistics_deg(const DisplayChannel& angle_deg, int width,
                                       const PixelRegion& region,
                                       const std::vector<bool>* keep = nullptr);

/// Focus metric: the mean squared intensity gradient (forward differences in x and y, both pixels
/// of a difference inside the region, finite and unflagged), in (units/pixel)². A sharper image of
/// the same scene has more gradient energy (Krotkov 1988; "Tenengrad" uses Sobel gradients); the
/// operator turns the lens to its maximum. NaN when the region has no pair of valid neighbours.
double gradient_energy(const DisplayChannel& channel, int width, const PixelRegion& region);

/// Pixels whose AoP means something: DoLP finite and ≥ `dolp_min`. Where DoLP ≈ 0 the AoP is the
/// angle of noise, uniform over 0–180°.
std::vector<bool> polarized_mask(const DisplayChannel& dolp, double dolp_min);

/// The region readout the page shows (GET /api/region): for the live S0 `{mean, std, count,
/// units}` and the focus metric `focus` {value, units}; for each cycle channel the same, AoP with
/// circular statistics over the pixels with DoLP ≥ `dolp_min` (`circular: true`, `masked`: pixels
/// left out by the threshold). Either image may be null. Throws tirpol::Error for a region out of
/// order or entirely outside the image, or a `dolp_min` outside [0, 1].
nlohmann::json region_readout(const DisplayImage* live, const DisplayImage* cycle,
                              const PixelRegion& region, double dolp_min);

}  // namespace tirpol::live
