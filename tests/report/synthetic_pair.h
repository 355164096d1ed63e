#pragma once
// A plausible measured/simulated Stokes pair for tests and demos: nine painted panels (3×3, as in
// the paper's Figure 4) in front of a cooler background, plus a warm sphere-like disc with radial
// emission polarization. The simulation is the noiseless truth plus Monte-Carlo noise (with S*_var
// channels); the "measurement" is the same scene shifted by (dx, dy) pixels plus detector noise
// (with S*_std channels), optionally with a bias added to one panel's S1.
// Header-only so that apps/ can reuse it for a demo without linking the tests.

#include <cmath>
#include <cstdint>
#include <random>
#include <string>

#include "tirpol/core/image.h"

namespace tirpol::report::test {

struct SyntheticPairOptions {
    int width = 192, height = 144;
    double shift_x_px = 0.0, shift_y_px = 0.0;  ///< measured(x, y) = scene(x − dx, y − dy)
    double measured_sigma = 0.05;   ///< σ of measured S0 in W/(m²·sr); σ(S1) = σ(S2) = √2 σ
    double simulated_sigma = 0.03;  ///< σ of the simulation's Monte-Carlo mean, all of S0..S2
    double s1_bias = 0.0;           ///< added to measured S1 inside panel 5 (the centre one)
    bool measured_uncertainty = true;  ///< write S0_std/S1_std/S2_std into the measured image
    bool simulated_variance = true;    ///< write S0_var/S1_var/S2_var into the simulated image
    std::uint32_t seed = 7;
};

/// Panel k (0..8) occupies [x0, x1] × [y0, y1] in scene pixels.
struct PanelBox {
    double x0, y0, x1, y1;
};
inline PanelBox panel_box(int k, int width, int height) {
    const double cell_w = width / 5.5, cell_h = height / 5.5;
    const int col = k % 3, row = k / 3;
    const double x0 = width * 0.08 + col * cell_w * 1.3, y0 = height * 0.08 + row * cell_h * 1.3;
    return {x0, y0, x0 + cell_w, y0 + cell_h};
}

/// Noise-free scene Stokes (S0, S1, S2) at continuous pixel position (x, y), W/(m²·sr).
inline void synthetic_scene(double x, double y, int width, int height, double out[3]) {
    auto step = [](double t) { return 1.0 / (1.0 + std::exp(-2.5 * t)); };  // edges about 1 px wide
    double s0 = 24.0 + 1.5 * y / height + 0.8 * x / width, s1 = 0.02, s2 = 0.0;
    for (int k = 0; k < 9; ++k) {
        const PanelBox b = panel_box(k, width, height);
        const double inside = step(x - b.x0) * step(b.x1 - x) * step(y - b.y0) * step(b.y1 - y);
        s0 += inside * (3.0 + 0.9 * k);     // panels warmer than the background
        s1 += inside * (-0.15 - 0.06 * k);  // emission-dominated: vertical, S1 < 0
        s2 += inside * 0.02 * (k % 3 - 1);
    }
    // A warm disc bottom-right: radial emission polarization (S1 ∝ cos 2φ, S2 ∝ sin 2φ).
    const double cx = width * 0.87, cy = height * 0.8, radius = height * 0.12;
    const double dx = x - cx, dy = y - cy, r = std::hypot(dx, dy);
    const double disc = step(radius - r);
    if (disc > 1e-6) {
        const double phi = std::atan2(-dy, dx), p = 0.8 * std::pow(std::min(r / radius, 1.0), 2.0);
        s0 += disc * 6.0;
        s1 += disc * p * std::cos(2.0 * phi);
        s2 += disc * p * std::sin(2.0 * phi);
    }
    out[0] = s0;
    out[1] = s1;
    out[2] = s2;
}

struct SyntheticPair {
    Image measured, simulated;
    std::string
        regions_yaml;  ///< panels 1, 5, 9, the disc and a background region, in measured pixels
};

inline SyntheticPair make_synthetic_pair(const SyntheticPairOptions& o) {
    std::mt19937 rng(o.seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    SyntheticPair pair{Image(o.width, o.height), Image(o.width, o.height), {}};
    const char* names[3] = {"S0", "S1", "S2"};
    const double sigma_m[3] = {o.measured_sigma, std::sqrt(2.0) * o.measured_sigma,
                               std::sqrt(2.0) * o.measured_sigma};
    const PanelBox centre = panel_box(4, o.width, o.height);
    for (int c = 0; c < 3; ++c) {
        pair.measured.add_channel(names[c]);
        pair.simulated.add_channel(names[c]);
        if (o.measured_uncertainty)
            pair.measured.add_channel(std::string(names[c]) + "_std",
                                      static_cast<float>(sigma_m[c]));
        if (o.simulated_variance)
            pair.simulated.add_channel(std::string(names[c]) + "_var",
                                       static_cast<float>(o.simulated_sigma * o.simulated_sigma));
    }
    for (int y = 0; y < o.height; ++y)
        for (int x = 0; x < o.width; ++x) {
            double truth_s[3], truth_m[3];
            synthetic_scene(x, y, o.width, o.height, truth_s);
            synthetic_scene(x - o.shift_x_px, y - o.shift_y_px, o.width, o.height, truth_m);
            const bool in_centre = x - o.shift_x_px > centre.x0 && x - o.shift_x_px < centre.x1 &&
                                   y - o.shift_y_px > centre.y0 && y - o.shift_y_px < centre.y1;
            const std::size_t i = pair.measured.index(x, y);
            for (int c = 0; c < 3; ++c) {
                double m = truth_m[c] + sigma_m[c] * normal(rng);
                if (c == 1 && in_centre) m += o.s1_bias;
                pair.measured.channel(names[c])[i] = static_cast<float>(m);
                pair.simulated.channel(names[c])[i] =
                    static_cast<float>(truth_s[c] + o.simulated_sigma * normal(rng));
            }
        }
    pair.measured.attributes()["units"] = std::string("W/(m²·sr)");
    pair.simulated.attributes()["units"] = std::string("W/(m²·sr)");

    // Regions inset by 3 px from the panel edges, in measured pixel coordinates.
    auto rect = [&](const std::string& name, double x0, double y0, double x1, double y1) {
        x0 += o.shift_x_px;
        x1 += o.shift_x_px;
        y0 += o.shift_y_px;
        y1 += o.shift_y_px;
        return "  - name: " + name + "\n    polygon: [[" + std::to_string(x0) + ", " +
               std::to_string(y0) + "], [" + std::to_string(x1) + ", " + std::to_string(y0) +
               "], [" + std::to_string(x1) + ", " + std::to_string(y1) + "], [" +
               std::to_string(x0) + ", " + std::to_string(y1) + "]]\n";
    };
    std::string yaml = "background: background\nregions:\n";
    for (int k : {0, 4, 8}) {
        const PanelBox b = panel_box(k, o.width, o.height);
        yaml += rect("panel_" + std::to_string(k + 1), b.x0 + 3, b.y0 + 3, b.x1 - 3, b.y1 - 3);
    }
    const double cx = o.width * 0.87, cy = o.height * 0.8, half = o.height * 0.12 * 0.6;
    yaml += rect("disc", cx - half, cy - half, cx + half, cy + half);
    yaml += rect("background", 3, o.height * 0.9, o.width * 0.6, o.height - 4);
    pair.regions_yaml = yaml;
    return pair;
}

}  // namespace tirpol::report::test
