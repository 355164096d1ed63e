#include "tirpol/calibration/microgrid_demosaic.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "microgrid_frame_check.h"
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

/// The same frame read without mirroring, for pixels at least 3 from every border (the stencils
/// reach ±3): most of the frame, so the hot loop skips the border tests.
struct InteriorMosaic {
    const float* data;
    int width;
    float at(int x, int y) const {
        return data[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                    static_cast<std::size_t>(x)];
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

/// Estimates of another analyzer's value at p = (x, y) from the directions s in which it sits at
/// the neighbour q = p + s, in the polarization-difference domain: the difference (other − own) is
/// taken at q and carried to p.
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
/// own(p+2s)|
/// + |other(q) − other(q+2s)| the variation along s, and the side that does not cross the edge
/// dominates: an unpolarized edge stays unpolarized.
///
/// Which region a pixel is in is decided, like Li et al.'s edge classifier, by how much the largest
/// and smallest directional variations differ: ratio (g_max + ε)/(g_min + ε) ≤ 3 is smooth, ≥ 8 an
/// edge, and the two estimates are blended linearly in between so the output has no seams.
template <std::size_t N>
struct DirectionalEstimate {
    std::array<double, N> other{};
    std::array<double, N> own_difference{};  ///< own(p) − own(p + 2s)
    std::array<double, N> gradient{};
    std::size_t count = 0;
    template <typename Frame>
    void add(const Frame& m, int x, int y, int dx, int dy, float own) {
        const double near = m.at(x + dx, y + dy);
        const double own_far = m.at(x + 2 * dx, y + 2 * dy);
        const double other_far = m.at(x + 3 * dx, y + 3 * dy);
        other[count] = near;
        own_difference[count] = static_cast<double>(own) - own_far;
        gradient[count] = std::abs(own_difference[count]) + std::abs(near - other_far);
        ++count;
    }
    float value(double epsilon) const {
        double g_min = gradient[0], g_max = gradient[0];
        for (double g : gradient) {
            g_min = std::min(g_min, g);
            g_max = std::max(g_max, g);
        }
        const double ratio = (g_max + epsilon) / (g_min + epsilon);
        const double edge =
            std::clamp((ratio - kSmoothRatio) / (kEdgeRatio - kSmoothRatio), 0.0, 1.0);
        double smooth = 0.0, weighted = 0.0, weight_sum = 0.0;
        for (std::size_t i = 0; i < N; ++i) {
            smooth += other[i] + 0.375 * own_difference[i];
            const double w = 1.0 / ((epsilon + gradient[i]) * (epsilon + gradient[i]));
            weighted += w * (other[i] + 0.5 * own_difference[i]);
            weight_sum += w;
        }
        smooth /= static_cast<double>(N);
        return static_cast<float>((1.0 - edge) * smooth + edge * weighted / weight_sum);
    }
    static constexpr double kSmoothRatio = 3.0;
    static constexpr double kEdgeRatio = 8.0;
};

template <typename Frame>
void newton_pixel(const Frame& m, int x, int y, std::size_t o, double epsilon,
                  DemosaicedFrame& out) {
    const int own_cell = (y & 1) * 2 + (x & 1);
    const float own = m.at(x, y);
    out.planes[static_cast<std::size_t>(own_cell)][o] = own;
    DirectionalEstimate<2> horizontal, vertical;
    DirectionalEstimate<4> diagonal;
    horizontal.add(m, x, y, -1, 0, own);
    horizontal.add(m, x, y, 1, 0, own);
    vertical.add(m, x, y, 0, -1, own);
    vertical.add(m, x, y, 0, 1, own);
    diagonal.add(m, x, y, -1, -1, own);
    diagonal.add(m, x, y, 1, -1, own);
    diagonal.add(m, x, y, -1, 1, own);
    diagonal.add(m, x, y, 1, 1, own);
    out.planes[static_cast<std::size_t>(own_cell ^ 1)][o] = horizontal.value(epsilon);
    out.planes[static_cast<std::size_t>(own_cell ^ 2)][o] = vertical.value(epsilon);
    out.planes[static_cast<std::size_t>(own_cell ^ 3)][o] = diagonal.value(epsilon);
}

void newton(const Mosaic& m, DemosaicedFrame& out) {
    // ε (1 % of the mean signal) keeps flat, noise-free regions (g ≈ 0 on all sides) in the
    // symmetric branch and sets the scale below which a variation is not an edge.
    double mean_abs = 0.0;
    const std::size_t n = static_cast<std::size_t>(m.width) * static_cast<std::size_t>(m.height);
    for (std::size_t i = 0; i < n; ++i) mean_abs += std::abs(static_cast<double>(m.data[i]));
    const double epsilon = 1e-2 * (mean_abs / static_cast<double>(n)) + 1e-30;
    const InteriorMosaic interior{m.data, m.width};
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x) {
            const std::size_t o = static_cast<std::size_t>(y) * static_cast<std::size_t>(m.width) +
                                  static_cast<std::size_t>(x);
            if (x >= 3 && y >= 3 && x < m.width - 3 && y < m.height - 3)
                newton_pixel(interior, x, y, o, epsilon, out);
            else
                newton_pixel(m, x, y, o, epsilon, out);
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
            newton(m, out);
            break;
    }
    return out;
}

}  // namespace tirpol::calibration
