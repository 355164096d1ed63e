#include "tirpol/calibration/stokes_reduction.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "tirpol/core/error.h"
#include "tirpol/core/geometry.h"
#include "tirpol/core/polarizer_angle.h"
#include "validate.h"

namespace tirpol::calibration {

namespace {
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
const double kAopStdCapDeg = 180.0 / std::sqrt(12.0);

const AnalyzerImage& image_for(const std::vector<AnalyzerImage>& images, double angle_deg) {
    for (const auto& im : images)
        if (same_polarizer_angle(im.angle_deg, angle_deg)) return im;
    std::string present;
    for (const auto& im : images) present += (present.empty() ? "" : ", ") + fmt::format("{:g}°", im.angle_deg);
    fail("no image at analyzer angle {:g}° (the analyzer model needs it); images present at: {}", angle_deg,
         present.empty() ? "none" : present);
}
}  // namespace

Image reduce_stokes(const std::vector<AnalyzerImage>& images, int width, int height, const AnalyzerModel& model,
                    const WireGridCalibration* wire_grid, const ReductionOptions& options) {
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    const Eigen::Matrix3Xd drm = model.data_reduction_matrix();
    const std::size_t n_angles = model.positions.size();

    // Validate everything first: no partial output for a bad input.
    std::vector<const AnalyzerImage*> inputs;
    std::vector<const WireGridPosition*> grid;
    bool have_std = true;
    for (const auto& pos : model.positions) {
        const AnalyzerImage& im = image_for(images, pos.nominal_angle_deg);
        detail::check_plane(im.signal, n, im.source, width, height);
        if (im.signal_std.empty())
            have_std = false;
        else
            detail::check_plane(im.signal_std, n, im.source + " (std)", width, height);
        inputs.push_back(&im);
        if (wire_grid) {
            const WireGridPosition& g = wire_grid->at(pos.nominal_angle_deg);
            if (g.tau.size() != n)
                fail("wire-grid calibration is {}×{}; the images are {}×{}", wire_grid->width, wire_grid->height, width,
                     height);
            grid.push_back(&g);
        }
    }

    // The wire-grid fit's own error, when known, is part of every reduced image's uncertainty.
    const bool grid_covariance =
        wire_grid && std::all_of(grid.begin(), grid.end(), [](const auto* g) { return g->has_covariance(); });

    Image out(width, height);
    auto& s0 = out.add_channel("S0");
    auto& s1 = out.add_channel("S1");
    auto& s2 = out.add_channel("S2");
    auto& dolp = out.add_channel("DoLP");
    auto& aop = out.add_channel("AoP");
    std::vector<float>*s0_std = nullptr, *s1_std = nullptr, *s2_std = nullptr, *dolp_std = nullptr, *aop_std = nullptr;
    if (have_std) {
        out.attributes()["std_includes"] = std::string(
            grid_covariance ? "temporal noise and the wire-grid calibration's fit error" : "temporal noise");
        s0_std = &out.add_channel("S0_std");
        s1_std = &out.add_channel("S1_std");
        s2_std = &out.add_channel("S2_std");
        dolp_std = &out.add_channel("DoLP_std");
        aop_std = &out.add_channel("AoP_std");
    }
    std::vector<float*> slar_p(n_angles, nullptr);
    if (options.include_slar)
        for (std::size_t k = 0; k < n_angles; ++k) {
            slar_p[k] = out.add_channel("L_SLAR_" + polarizer_angle_tag(model.positions[k].nominal_angle_deg)).data();
        }

    // Hot loop on plain arrays (no per-pixel Eigen temporaries of dynamic size): per angle k, the
    // DRM column (w0k, w1k, w2k) and the signal, σ, τ and B planes.
    std::vector<double> w(3 * n_angles), tau_const(n_angles), b_const(n_angles);
    for (std::size_t k = 0; k < n_angles; ++k) {
        for (std::size_t r = 0; r < 3; ++r)
            w[3 * k + r] = drm(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k));
        tau_const[k] = model.positions[k].relative_transmission;
        b_const[k] = model.positions[k].background;
    }
    std::vector<const float*> sig_p(n_angles), std_p(n_angles, nullptr), tau_p(n_angles, nullptr), b_p(n_angles, nullptr);
    std::vector<const float*> tau_var_p(n_angles, nullptr), b_var_p(n_angles, nullptr), tau_b_cov_p(n_angles, nullptr);
    for (std::size_t k = 0; k < n_angles; ++k) {
        sig_p[k] = inputs[k]->signal.data();
        if (have_std) std_p[k] = inputs[k]->signal_std.data();
        if (wire_grid) {
            tau_p[k] = grid[k]->tau.data();
            b_p[k] = grid[k]->background.data();
        }
        if (grid_covariance) {
            tau_var_p[k] = grid[k]->tau_var.data();
            b_var_p[k] = grid[k]->background_var.data();
            tau_b_cov_p[k] = grid[k]->tau_background_cov.data();
        }
    }
    int unrealizable = 0;
    for (std::size_t i = 0; i < n; ++i) {
        double s[3] = {0.0, 0.0, 0.0};
        double c00 = 0.0, c11 = 0.0, c22 = 0.0, c01 = 0.0, c02 = 0.0, c12 = 0.0;
        for (std::size_t k = 0; k < n_angles; ++k) {
            // L_SLAR = (I − B)/τ with the per-pixel wire-grid maps, else the analyzer's (t_k, b_k).
            const double tau = wire_grid ? tau_p[k][i] : tau_const[k];
            const double b = wire_grid ? b_p[k][i] : b_const[k];
            const double l = (sig_p[k][i] - b) / tau;
            if (slar_p[k]) slar_p[k][i] = static_cast<float>(l);
            const double* wk = &w[3 * k];
            s[0] += wk[0] * l;
            s[1] += wk[1] * l;
            s[2] += wk[2] * l;
            if (have_std) {
                // Independent per-angle errors: Cov(S) = W⁺·diag(σ²)·W⁺ᵀ (Tyo et al. 2006, §4.3). With
                // the grid's fitted (τ, B) uncertain too (each angle fitted from its own frames), first order
                // in l = (I − B)/τ: Var l = (σ_I² + Var B + l² Var τ + 2 l Cov(τ, B)) / τ².
                double var = static_cast<double>(std_p[k][i]) * std_p[k][i];
                if (grid_covariance)
                    var += b_var_p[k][i] + l * l * tau_var_p[k][i] + 2.0 * l * tau_b_cov_p[k][i];
                var /= tau * tau;
                c00 += wk[0] * wk[0] * var;
                c11 += wk[1] * wk[1] * var;
                c22 += wk[2] * wk[2] * var;
                c01 += wk[0] * wk[1] * var;
                c02 += wk[0] * wk[2] * var;
                c12 += wk[1] * wk[2] * var;
            }
        }
        double pl = std::sqrt(s[1] * s[1] + s[2] * s[2]);
        if (pl > s[0] && s[0] >= 0.0) {
            ++unrealizable;
            if (options.project_to_realizable && pl > 0.0) {
                s[1] *= s[0] / pl;
                s[2] *= s[0] / pl;
                pl = s[0];
            }
        }
        s0[i] = static_cast<float>(s[0]);
        s1[i] = static_cast<float>(s[1]);
        s2[i] = static_cast<float>(s[2]);
        dolp[i] = s[0] > 0.0 ? static_cast<float>(pl / s[0]) : kNaN;
        double psi = rad_to_deg(0.5 * std::atan2(s[2], s[1]));
        if (psi < 0.0) psi += 180.0;
        aop[i] = static_cast<float>(psi);
        if (have_std) {
            (*s0_std)[i] = static_cast<float>(std::sqrt(c00));
            (*s1_std)[i] = static_cast<float>(std::sqrt(c11));
            (*s2_std)[i] = static_cast<float>(std::sqrt(c22));
            // First-order propagation to DoLP = |(S1,S2)|/S0 and AoP = ½·atan2(S2, S1): σ² = gᵀ·Cov·g.
            if (s[0] > 0.0 && pl > 0.0) {
                const double g0 = -pl / (s[0] * s[0]), g1 = s[1] / (s[0] * pl), g2 = s[2] / (s[0] * pl);
                const double var_dolp = g0 * g0 * c00 + g1 * g1 * c11 + g2 * g2 * c22 +
                                        2.0 * (g0 * g1 * c01 + g0 * g2 * c02 + g1 * g2 * c12);
                const double a1 = -0.5 * s[2] / (pl * pl), a2 = 0.5 * s[1] / (pl * pl);
                const double var_aop = a1 * a1 * c11 + a2 * a2 * c22 + 2.0 * a1 * a2 * c12;
                (*dolp_std)[i] = static_cast<float>(std::sqrt(std::max(0.0, var_dolp)));
                // Where DoLP ≈ its noise the linearisation diverges; an AoP known to nothing is uniform on
                // [0°, 180°), σ = 180°/√12, the cap.
                (*aop_std)[i] = static_cast<float>(std::min(kAopStdCapDeg, rad_to_deg(std::sqrt(std::max(0.0, var_aop)))));
            } else {
                (*dolp_std)[i] = kNaN;
                (*aop_std)[i] = static_cast<float>(kAopStdCapDeg);
            }
        }
    }

    auto& a = out.attributes();
    a["units"] = options.units;
    a["units_S0"] = options.units;
    a["units_S1"] = options.units;
    a["units_S2"] = options.units;
    a["units_DoLP"] = std::string("1");
    a["units_AoP"] = std::string("deg");
    a["stokes_convention"] =
        std::string("S1 = I0 - I90, S2 = I45 - I135; 0 deg along image rows (+x), 90 deg to the top of the image");
    std::vector<double> angles, drm_values;
    for (const auto& p : model.positions) angles.push_back(p.nominal_angle_deg);
    for (Eigen::Index r = 0; r < 3; ++r)
        for (Eigen::Index c = 0; c < drm.cols(); ++c) drm_values.push_back(drm(r, c));
    a["analyzer_angles_deg"] = angles;
    a["drm"] = drm_values;
    a["unrealizable_pixels"] = unrealizable;
    a["wire_grid_corrected"] = wire_grid ? 1 : 0;
    return out;
}

}  // namespace tirpol::calibration
