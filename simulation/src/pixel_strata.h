#pragma once
// Latin-hypercube strata of a pixel's samples (McKay, Beckman & Conover, Technometrics 21, 1979):
// in each stratified dimension, the pixel's spp samples take one stratum [j/spp, (j+1)/spp) each, in
// an order shuffled per dimension and per pixel (see shuffle). Each sample stays uniform in every
// dimension (so the estimate stays unbiased), but a pixel can no longer draw all its samples on one
// side of a rare event: with independent draws a 16-sample pixel that views glossy paint through a
// mirror drew no diffuse-lobe sample with probability 0.91¹⁶ = 22 %, and its mean and variance then
// both missed the lobe (|z| up to 45 in an isothermal enclosure, issue 13); with strata it draws
// ⌊16·0.09⌋ or ⌈16·0.09⌉ of them.

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "tirpol/simulation/rng.h"

namespace tirpol::simulation::detail {

/// The dimensions stratified per pixel: the sub-pixel position (edges and thin objects) and the
/// two numbers that sample the first non-delta reflection (which lobe, and where in it). Wavelength
/// strata follow the sample index instead (renderer.cpp), which the variance estimator relies on.
enum class StratifiedDimension { subpixel_x, subpixel_y, scatter_u1, scatter_u2 };
inline constexpr std::size_t kStratifiedDimensions = 4;

class PixelStrata {
public:
    explicit PixelStrata(int spp) : m_spp(spp) {
        for (auto& order : m_order) order.resize(static_cast<std::size_t>(spp));
    }

    /// Draws the pixel's stratum orders from a stream of its own (sample index −1), so they are a
    /// function of (seed, pixel) only, like every other draw. The renderer's variance estimator
    /// compares samples 2k and 2k + 1 (neighbouring wavelength strata): in every dimension here, one
    /// of them takes a stratum of the lower half and the other one of the upper half (each half
    /// shuffled, the two swapped at random), so a rare region (a lobe drawn with probability ≤ ½)
    /// never holds both samples of a pair, whose difference would then hide it from the estimate
    /// (with independent shuffles: |z| up to 17 at 16 spp). Each sample's stratum stays uniform and
    /// independent between dimensions, so the mean stays unbiased; the pairs' differences include
    /// the difference between the halves, so the estimate errs on the large side. (Pairing
    /// neighbouring strata instead made a pair's two paths nearly identical at high spp and the
    /// estimate blind: z up to 600.) An odd spp (a closing triple) shuffles every stratum.
    void shuffle(std::uint64_t seed, std::uint64_t pixel) {
        SampleStream rng(seed, pixel, ~std::uint64_t{0});
        const int half = m_spp / 2;
        for (auto& order : m_order) {
            for (int j = 0; j < m_spp; ++j) order[static_cast<std::size_t>(j)] = j;
            if (m_spp % 2 != 0) {
                shuffle_range(order, 0, m_spp, rng);
                continue;
            }
            shuffle_range(order, 0, half, rng);  // lower strata, then upper strata
            shuffle_range(order, half, m_spp, rng);
            m_scratch = order;
            for (int k = 0; k < half; ++k) {
                const int swap = rng.next() < 0.5 ? 1 : 0;
                order[static_cast<std::size_t>(2 * k + swap)] = m_scratch[static_cast<std::size_t>(k)];
                order[static_cast<std::size_t>(2 * k + 1 - swap)] = m_scratch[static_cast<std::size_t>(half + k)];
            }
        }
    }

    /// Sample `sample`'s value in `dimension`: uniform in its stratum, `jitter` in [0, 1) placing it.
    double value(StratifiedDimension dimension, int sample, double jitter) const {
        const int stratum = m_order[static_cast<std::size_t>(dimension)][static_cast<std::size_t>(sample)];
        return (stratum + jitter) / m_spp;
    }

private:
    /// Fisher–Yates shuffle of order[begin, end).
    static void shuffle_range(std::vector<int>& order, int begin, int end, SampleStream& rng) {
        for (int j = end - 1; j > begin; --j) {
            const auto k = static_cast<std::size_t>(begin + static_cast<int>(rng.next() * (j - begin + 1)));
            std::swap(order[static_cast<std::size_t>(j)], order[k]);
        }
    }

    int m_spp;
    std::vector<int> m_scratch;  // reused: no allocation per pixel
    std::array<std::vector<int>, kStratifiedDimensions> m_order;
};

}  // namespace tirpol::simulation::detail
