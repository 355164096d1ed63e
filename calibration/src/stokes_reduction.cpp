#include "tirpol/calibration/stokes_reduction.h"

#include <Eigen/Dense>
#include <cmath>
#include <limits>

#include "tirpol/core/error.h"
#include "tirpol/core/geometry.h"
#include "validate.h"

namespace tirpol::calibration {

namespace {
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
const double kAopStdCapDeg = 180.0 / std::sqrt(12.0);

const AnalyzerImage& image_for(const std::vector<AnalyzerImage>& images, double angle_deg) {
    for (const auto& im : images)
        if (std::abs(im.angle_deg - angle_deg) < 0.01) return im;
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

    Image out(width, height);
    auto& s0 = out.add_channel("S0");
    auto& s1 = out.add_channel("S1");
    auto& s2 = out.add_channel("S2");
    auto& dolp = out.add_channel("DoLP");
    auto& aop = out.add_channel("AoP");
    std::vector<float>*s0_std = nullptr, *s1_std = nullptr, *s2_std = nullptr, *dolp_std = nullptr, *aop_std = nullptr;
    if (have_std) {
        s0_std = &out.add_channel("S0_std");
        s1_std = &out.add_channel("S1_std");
        s2_std = &out.add_channel("S2_std");
        dolp_std = &out.add_channel("DoLP_std");
        aop_std = &out.add_channel("AoP_std");
    }

    std::vector<double> scale(n_angles), bias(n_angles);
    Eigen::VectorXd l(static_cast<Eigen::Index>(n_angles)), var(static_cast<Eigen::Index>(n_angles));
    int unrealizable = 0;
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t k = 0; k < n_angles; ++k) {
            // L_SLAR = (I − B)/τ with the per-pixel wire-grid maps, else the analyzer's (t_k, b_k).
            const double tau = wire_grid ? grid[k]->tau[i] : model.positions[k].relative_transmission;
            const double b = wire_grid ? grid[k]->background[i] : model.positions[k].background;
            const auto ki = static_cast<Eigen::Index>(k);
            l[ki] = (inputs[k]->signal[i] - b) / tau;
            if (have_std) var[ki] = std::pow(inputs[k]->signal_std[i] / tau, 2);
        }
        Eigen::Vector3d s = drm * l;
        const double p_lin = std::hypot(s[1], s[2]);
        if (p_lin > s[0] && s[0] >= 0.0) {
            ++unrealizable;
            if (options.project_to_realizable && p_lin > 0.0) {
                s[1] *= s[0] / p_lin;
                s[2] *= s[0] / p_lin;
            }
        }
        s0[i] = static_cast<float>(s[0]);
        s1[i] = static_cast<float>(s[1]);
        s2[i] = static_cast<float>(s[2]);
        const double pl = std::hypot(s[1], s[2]);
        dolp[i] = s[0] > 0.0 ? static_cast<float>(pl / s[0]) : kNaN;
        double psi = rad_to_deg(0.5 * std::atan2(s[2], s[1]));
        if (psi < 0.0) psi += 180.0;
        aop[i] = static_cast<float>(psi);
        if (have_std) {
            // Independent per-angle errors: Cov(S) = W⁺·diag(σ²)·W⁺ᵀ (Tyo et al. 2006, §4.3).
            const Eigen::Matrix3d cov = drm * var.asDiagonal() * drm.transpose();
            (*s0_std)[i] = static_cast<float>(std::sqrt(cov(0, 0)));
            (*s1_std)[i] = static_cast<float>(std::sqrt(cov(1, 1)));
            (*s2_std)[i] = static_cast<float>(std::sqrt(cov(2, 2)));
            // First-order propagation to DoLP = |(S1,S2)|/S0 and AoP = ½·atan2(S2, S1).
            if (s[0] > 0.0 && pl > 0.0) {
                const Eigen::Vector3d g_dolp{-pl / (s[0] * s[0]), s[1] / (s[0] * pl), s[2] / (s[0] * pl)};
                const Eigen::Vector3d g_aop{0.0, -0.5 * s[2] / (pl * pl), 0.5 * s[1] / (pl * pl)};
                (*dolp_std)[i] = static_cast<float>(std::sqrt(g_dolp.dot(cov * g_dolp)));
                // Where DoLP ≈ its noise the linearisation diverges; an AoP known to nothing is uniform on
                // [0°, 180°), σ = 180°/√12, the cap.
                (*aop_std)[i] = static_cast<float>(std::min(kAopStdCapDeg, rad_to_deg(std::sqrt(g_aop.dot(cov * g_aop)))));
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
