#pragma once
// Synthetic scenes with known full-resolution Stokes for the microgrid tests: a smooth polarized
// field, an unpolarized step edge and a polarized edge, each pixel the mean over its footprint
// (8×8 sub-samples), so an edge inside a pixel gives that pixel a partial value as a real detector
// does.

#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

namespace tirpol::calibration::testing {

struct StokesScene {
    int width = 0, height = 0;
    std::vector<float> s0, s1, s2;
    std::vector<unsigned char> edge_mask;  ///< pixels within 3 px of an edge (empty: none)
};

struct StokesPoint {
    double s0, s1, s2;
};

/// Pixel (x, y) covers [x, x+1) × [y, y+1); `field` is evaluated at 8×8 points of it and averaged.
inline StokesScene integrate_scene(int width, int height,
                                   const std::function<StokesPoint(double, double)>& field) {
    StokesScene scene{width, height, {}, {}, {}, {}};
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    scene.s0.resize(n);
    scene.s1.resize(n);
    scene.s2.resize(n);
    constexpr int kSub = 8;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double a = 0, b = 0, c = 0;
            for (int j = 0; j < kSub; ++j)
                for (int i = 0; i < kSub; ++i) {
                    const StokesPoint p = field(x + (i + 0.5) / kSub, y + (j + 0.5) / kSub);
                    a += p.s0;
                    b += p.s1;
                    c += p.s2;
                }
            const std::size_t k = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                  static_cast<std::size_t>(x);
            scene.s0[k] = static_cast<float>(a / (kSub * kSub));
            scene.s1[k] = static_cast<float>(b / (kSub * kSub));
            scene.s2[k] = static_cast<float>(c / (kSub * kSub));
        }
    return scene;
}

inline StokesPoint polarized(double s0, double dolp, double aop_deg) {
    const double two_psi = 2.0 * aop_deg * std::numbers::pi / 180.0;
    return {s0, s0 * dolp * std::cos(two_psi), s0 * dolp * std::sin(two_psi)};
}

/// Smoothly varying S0 (±30 %, periods 37 and 53 px) and, unless `unpolarized`, DoLP (0.1–0.3,
/// period 61 px along the diagonal) and AoP (−10°…70°, periods 71 px in x and 76 px in y): a
/// texture of polarization as strong as the texture of intensity.
inline StokesScene smooth_scene(int width, int height, bool unpolarized = false) {
    const double tau = 2.0 * std::numbers::pi;
    return integrate_scene(width, height, [tau, unpolarized](double x, double y) {
        const double s0 = 100.0 + 30.0 * std::sin(tau * x / 37.0) * std::cos(tau * y / 53.0);
        const double dolp = unpolarized ? 0.0 : 0.2 + 0.1 * std::sin(tau * (x + y) / 61.0);
        const double aop = 30.0 + 40.0 * std::sin(tau * x / 71.0 + tau * y / 19.0 * 0.25);
        return polarized(s0, dolp, aop);
    });
}

/// edge_mask: the pixels within 3 px (horizontally) of the line x = x0 + slope·(y − height/2).
inline void mark_edge(StokesScene& scene, int width, int height, double x0, double slope) {
    const double mid = height / 2.0;
    scene.edge_mask.assign(scene.s0.size(), 0);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            if (std::abs(x + 0.5 - (x0 + slope * (y + 0.5 - mid))) <= 3.0)
                scene.edge_mask[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                static_cast<std::size_t>(x)] = 1;
}

/// A step of S0 from 50 to 150 along the line x = x0 + slope·(y − height/2), unpolarized on both
/// sides; edge_mask marks the pixels within 3 px (horizontally) of the line.
inline StokesScene unpolarized_edge_scene(int width, int height, double x0, double slope) {
    const double mid = height / 2.0;
    StokesScene scene = integrate_scene(width, height, [=](double x, double y) {
        return StokesPoint{x < x0 + slope * (y - mid) ? 50.0 : 150.0, 0.0, 0.0};
    });
    mark_edge(scene, width, height, x0, slope);
    return scene;
}

/// Unpolarized S0 = 80 left of the slanted line, DoLP 0.3 at AoP 30° with S0 = 120 right of it.
inline StokesScene polarized_edge_scene(int width, int height, double x0, double slope) {
    const double mid = height / 2.0;
    StokesScene scene = integrate_scene(width, height, [=](double x, double y) {
        return x < x0 + slope * (y - mid) ? StokesPoint{80.0, 0.0, 0.0}
                                          : polarized(120.0, 0.3, 30.0);
    });
    mark_edge(scene, width, height, x0, slope);
    return scene;
}

}  // namespace tirpol::calibration::testing
