#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "microgrid_frame_check.h"
#include "microgrid_newton_row.h"
#include "tirpol/calibration/microgrid_stokes.h"
#include "tirpol/core/error.h"

namespace tirpol::calibration {

namespace {

/// Mirror about the first and last pixel: index −i maps to i and W−1+i to W−1−i, so an even
/// offset keeps the parity of the index and therefore the analyzer of the cell position.
inline int mirror(int i, int n) {
    if (i < 0) return -i;
    if (i >= n) return 2 * (n - 1) - i;
    return i;
}

struct Mosaic {
    const float* data;
    int width;
    int height;
    float at(int x, int y) const {
        return data[static_cast<std::size_t>(mirror(y, height)) * static_cast<std::size_t>(width) +
                    static_cast<std::size_t>(mirror(x, width))];
    }
};

void super_pixel(const Mosaic& m, DemosaicedFrame& out) {
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            const std::size_t o =
                static_cast<std::size_t>(y) * static_cast<std::size_t>(out.width) +
                static_cast<std::size_t>(x);
            for (int cell = 0; cell < 4; ++cell)
                out.planes[static_cast<std::size_t>(cell)][o] =
                    m.at(2 * x + (cell & 1), 2 * y + (cell >> 1));
        }
}

void bilinear(const Mosaic& m, DemosaicedFrame& out) {
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x) {
            const std::size_t o = static_cast<std::size_t>(y) * static_cast<std::size_t>(m.width) +
                                  static_cast<std::size_t>(x);
            const int own = (y & 1) * 2 + (x & 1);
            out.planes[static_cast<std::size_t>(own)][o] = m.at(x, y);
            out.planes[static_cast<std::size_t>(own ^ 1)][o] =
                0.5f * (m.at(x - 1, y) + m.at(x + 1, y));
            out.planes[static_cast<std::size_t>(own ^ 2)][o] =
                0.5f * (m.at(x, y - 1) + m.at(x, y + 1));
            out.planes[static_cast<std::size_t>(own ^ 3)][o] =
                0.25f *
                (m.at(x - 1, y - 1) + m.at(x + 1, y - 1) + m.at(x - 1, y + 1) + m.at(x + 1, y + 1));
        }
}

/// Newton-polynomial interpolation of polarization differences (microgrid_newton_row.h), after Li,
/// Zhao, Pan & Kong 2019. Estimates of another analyzer's value at p = (x, y) come from the
/// directions s in which it sits at the neighbour q = p + s; the difference (other − own) is taken
/// at q and carried to p.
///
/// Smooth region: own(q) is the quadratic (second-order Newton) polynomial through own(p − 2s),
/// own(p), own(p + 2s), and the two opposite directions are averaged, which gives
///   ½(other(p−s) + other(p+s)) + ⅛(2·own(p) − own(p−2s) − own(p+2s)),
/// exact whenever both analyzers' signals are quadratic with the same curvature (an unpolarized or
/// uniformly polarized smooth scene) and linear fields of any polarization. Written per direction
/// this is the mean of other(q) + ⅜(own(p) − own(p+2s)).
///
/// Edge: the symmetric stencil mixes both sides of an edge into a false polarization difference.
/// There each direction's one-sided estimate other(q) + ½(own(p) − own(p+2s)) (own(q) linear
/// between p and p + 2s, so it never reaches across p) is weighted by 1/(ε + g_s)², g_s = |own(p) −
/// own(p+2s)| + |other(q) − other(q+2s)| the variation along s, and the side that does not cross
/// the edge dominates: an unpolarized edge stays unpolarized.
///
/// Which region a pixel is in is decided, like Li et al.'s edge classifier, by how much the largest
/// and smallest directional variations differ: ratio (g_max + ε)/(g_min + ε) ≤ 3 is smooth, ≥ 8 an
/// edge, and the two estimates are blended linearly in between so the output has no seams.
void newton(std::span<const float> mosaic, int width, int height, DemosaicedFrame& out) {
    const detail::PaddedMosaic padded(mosaic.data(), width, height);
    const float epsilon = detail::newton_epsilon(mosaic.data(), mosaic.size());
    const auto w = static_cast<std::size_t>(width);
    std::vector<float> estimate[3];
    for (auto& row : estimate) row.resize(w);
    for (int y = 0; y < height; ++y) {
        detail::newton_row(padded, y, w, epsilon, estimate[0].data(), estimate[1].data(),
                           estimate[2].data());
        const float* own = padded.row(y, 0);
        const std::size_t start = static_cast<std::size_t>(y) * w;
        for (std::size_t x = 0; x < w; ++x) {
            const std::size_t own_cell = static_cast<std::size_t>(y & 1) * 2 + (x & 1);
            out.planes[own_cell][start + x] = own[x];
            for (std::size_t role = 1; role < 4; ++role)
                out.planes[own_cell ^ role][start + x] = estimate[role - 1][x];
        }
    }
}

}  // namespace

void detail::check_microgrid_size(std::size_t values, int width, int height,
                                  std::string_view source) {
    if (width < 4 || height < 4 || width % 2 != 0 || height % 2 != 0)
        fail(
            "{}: {}×{} pixels; a microgrid frame must have an even width and height of at least 4 "
            "(whole 2×2 cells)",
            source, width, height);
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    if (values != n)
        fail("{}: {} values for a {}×{} frame; expected {}", source, values, width, height, n);
}

void detail::check_microgrid_frame(std::span<const float> mosaic, int width, int height,
                                   std::string_view source) {
    check_microgrid_size(mosaic.size(), width, height, source);
    // Whether any value is Inf or NaN (exponent bits all set), by integer operations that the
    // compiler vectorises (a loop that stops at the first bad value does not); the slow loop below
    // only runs to name the pixel.
    std::uint32_t any_not_finite = 0;
    for (const float v : mosaic) {
        std::uint32_t bits = 0;
        std::memcpy(&bits, &v, sizeof bits);
        any_not_finite |= static_cast<std::uint32_t>((bits & 0x7f800000u) == 0x7f800000u);
    }
    if (any_not_finite == 0) return;
    for (std::size_t i = 0; i < mosaic.size(); ++i)
        if (!std::isfinite(mosaic[i]))
            fail("{}: pixel (x={}, y={}) is {}; expected finite values", source,
                 i % static_cast<std::size_t>(width), i / static_cast<std::size_t>(width),
                 mosaic[i]);
}

std::string_view demosaic_method_name(DemosaicMethod method) {
    switch (method) {
        case DemosaicMethod::SuperPixel:
            return "super-pixel";
        case DemosaicMethod::Bilinear:
            return "bilinear";
        case DemosaicMethod::Newton:
            return "newton";
    }
    return "unknown";
}

std::string_view demosaic_method_reference(DemosaicMethod method) {
    switch (method) {
        case DemosaicMethod::SuperPixel:
            return "";
        case DemosaicMethod::Bilinear:
            return "Ratliff, LaCasse & Tyo, Opt. Express 17(11), 9112-9125 (2009)";
        case DemosaicMethod::Newton:
            return "after Li, Zhao, Pan & Kong, Opt. Express 27(2), 1376-1391 (2019): "
                   "edge-directed Newton "
                   "interpolation of polarization differences";
    }
    return "";
}

DemosaicMethod parse_demosaic_method(std::string_view text, std::string_view context) {
    for (DemosaicMethod m :
         {DemosaicMethod::SuperPixel, DemosaicMethod::Bilinear, DemosaicMethod::Newton})
        if (text == demosaic_method_name(m)) return m;
    fail("{}: unknown demosaicing method '{}'; expected super-pixel, bilinear or newton", context,
         text);
}

DemosaicedFrame demosaic_microgrid(std::span<const float> mosaic, int width, int height,
                                   const MicrogridPattern& pattern, DemosaicMethod method,
                                   std::string_view source) {
    detail::check_microgrid_frame(mosaic, width, height, source);
    DemosaicedFrame out;
    out.method = method;
    out.angles_deg = pattern.angles_deg();
    const bool half = method == DemosaicMethod::SuperPixel;
    out.width = half ? width / 2 : width;
    out.height = half ? height / 2 : height;
    for (auto& plane : out.planes)
        plane.assign(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height),
                     0.0f);
    const Mosaic m{mosaic.data(), width, height};
    switch (method) {
        case DemosaicMethod::SuperPixel:
            super_pixel(m, out);
            break;
        case DemosaicMethod::Bilinear:
            bilinear(m, out);
            break;
        case DemosaicMethod::Newton:
            newton(mosaic, width, height, out);
            break;
    }
    return out;
}

}  // namespace tirpol::calibration
