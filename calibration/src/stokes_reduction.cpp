#include "tirpol/calibration/stokes_reduction.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "stokes_attributes.h"
#include "stokes_uncertainty.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/geometry.h"
#include "tirpol/core/interrupt_signals.h"
#include "tirpol/core/stokes.h"
#include "validate.h"

namespace tirpol::calibration {

namespace {
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
const double kAopStdCapDeg = 180.0 / std::sqrt(12.0);

const AnalyzerPlanes& image_for(const std::vector<AnalyzerPlanes>& images, double angle_deg) {
    for (const auto& im : images)
        if (same_polarizer_angle(im.angle_deg, angle_deg)) return im;
    std::string present;
    for (const auto& im : images)
        present += (present.empty() ? "" : ", ") + fmt::format("{:g}°", im.angle_deg);
    fail("no image at analyzer angle {:g}° (the analyzer model needs it); images present at: {}",
         angle_deg, present.empty() ? "none" : present);
}

/// The inputs in the model's angle order, checked before anything is computed.
struct ValidatedInputs {
    std::vector<const AnalyzerPlanes*> images;
    std::vector<const WireGridPosition*> grid;  ///< empty without a wire-grid calibration
    bool have_std = true;                       ///< every image has its σ plane
    bool grid_covariance = false;               ///< every grid position has the fit's (co)variances
};

/// Validates everything first: no partial output for a bad input.
ValidatedInputs validate(const std::vector<AnalyzerPlanes>& images, int width, int height,
                         const AnalyzerModel& model, const WireGridCalibration* wire_grid) {
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    ValidatedInputs v;
    for (const auto& pos : model.positions) {
        const AnalyzerPlanes& im = image_for(images, pos.nominal_angle_deg);
        detail::check_plane(im.signal, n, im.source, width, height);
        if (im.signal_std.empty())
            v.have_std = false;
        else
            detail::check_std_plane(im.signal_std, n, im.source + " (std)", width, height);
        v.images.push_back(&im);
        if (wire_grid) {
            const WireGridPosition& g = wire_grid->at(pos.nominal_angle_deg);
            if (g.tau.size() != n)
                fail("wire-grid calibration is {}×{}; the images are {}×{}", wire_grid->width,
                     wire_grid->height, width, height);
            v.grid.push_back(&g);
        }
    }
    // The wire-grid fit's own error, when known, is part of every reduced image's uncertainty.
    v.grid_covariance = wire_grid && std::all_of(v.grid.begin(), v.grid.end(),
                                                 [](const auto* g) { return g->has_covariance(); });
    return v;
}

/// Per angle k, the DRM column (w0k, w1k, w2k) and the signal, σ, τ and B planes as plain arrays:
/// the hot loop makes no per-pixel Eigen temporaries of dynamic size.
struct AnglePlanes {
    std::size_t n_angles = 0;
    std::vector<double> w, tau_const, b_const;
    std::vector<const float*> signal, sigma, tau, b, tau_var, b_var, tau_b_cov;
    std::vector<float*> slar;  ///< L_SLAR outputs, null when not requested

    AnglePlanes(const ValidatedInputs& v, const AnalyzerModel& model, const Eigen::Matrix3Xd& drm)
        : n_angles(model.positions.size()),
          w(3 * n_angles),
          tau_const(n_angles),
          b_const(n_angles),
          signal(n_angles),
          sigma(n_angles, nullptr),
          tau(n_angles, nullptr),
          b(n_angles, nullptr),
          tau_var(n_angles, nullptr),
          b_var(n_angles, nullptr),
          tau_b_cov(n_angles, nullptr),
          slar(n_angles, nullptr) {
        for (std::size_t k = 0; k < n_angles; ++k) {
            for (std::size_t r = 0; r < 3; ++r)
                w[3 * k + r] = drm(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k));
            tau_const[k] = model.positions[k].relative_transmission;
            b_const[k] = model.positions[k].background;
            signal[k] = v.images[k]->signal.data();
            if (v.have_std) sigma[k] = v.images[k]->signal_std.data();
            if (!v.grid.empty()) {
                tau[k] = v.grid[k]->tau.data();
                b[k] = v.grid[k]->background.data();
            }
            if (v.grid_covariance) {
                tau_var[k] = v.grid[k]->tau_var.data();
                b_var[k] = v.grid[k]->background_var.data();
                tau_b_cov[k] = v.grid[k]->tau_background_cov.data();
            }
        }
    }
};

/// One pixel's Stokes vector (S0, S1, S2) and the upper triangle of its covariance.
struct PixelStokes {
    double s[3] = {0.0, 0.0, 0.0};
    double c00 = 0.0, c11 = 0.0, c22 = 0.0, c01 = 0.0, c02 = 0.0, c12 = 0.0;
};

/// Solve: S = W⁺·L_SLAR at pixel i, with Cov(S) when the inputs carry σ.
PixelStokes solve_pixel(const AnglePlanes& p, std::size_t i, bool have_std) {
    PixelStokes r;
    for (std::size_t k = 0; k < p.n_angles; ++k) {
        // L_SLAR = (I − B)/τ with the per-pixel wire-grid maps, else the analyzer's (t_k, b_k).
        const double tau = p.tau[k] ? p.tau[k][i] : p.tau_const[k];
        const double b = p.b[k] ? p.b[k][i] : p.b_const[k];
        const double l = (p.signal[k][i] - b) / tau;
        if (p.slar[k]) p.slar[k][i] = static_cast<float>(l);
        const double* wk = &p.w[3 * k];
        r.s[0] += wk[0] * l;
        r.s[1] += wk[1] * l;
        r.s[2] += wk[2] * l;
        if (have_std) {
            // Independent per-angle errors: Cov(S) = W⁺·diag(σ²)·W⁺ᵀ (Tyo et al. 2006, §4.3). With
            // the grid's fitted (τ, B) uncertain too (each angle fitted from its own frames), first
            // order in l = (I − B)/τ: Var l = (σ_I² + Var B + l² Var τ + 2 l Cov(τ, B)) / τ².
            double var = static_cast<double>(p.sigma[k][i]) * p.sigma[k][i];
            if (p.tau_var[k])
                var += p.b_var[k][i] + l * l * p.tau_var[k][i] + 2.0 * l * p.tau_b_cov[k][i];
            var /= tau * tau;
            r.c00 += wk[0] * wk[0] * var;
            r.c11 += wk[1] * wk[1] * var;
            r.c22 += wk[2] * wk[2] * var;
            r.c01 += wk[0] * wk[1] * var;
            r.c02 += wk[0] * wk[2] * var;
            r.c12 += wk[1] * wk[2] * var;
        }
    }
    return r;
}

/// The output planes; the σ planes are null without input σ.
struct OutputPlanes {
    std::vector<float>&s0, &s1, &s2, &dolp, &aop;
    std::vector<float>*s0_std = nullptr, *s1_std = nullptr, *s2_std = nullptr, *dolp_std = nullptr,
    *aop_std = nullptr;
};

OutputPlanes add_output_channels(Image& out, const ValidatedInputs& v, const AnalyzerModel& model,
                                 const ReductionOptions& options, AnglePlanes& planes) {
    OutputPlanes o{out.add_channel("S0"), out.add_channel("S1"), out.add_channel("S2"),
                   out.add_channel("DoLP"), out.add_channel("AoP")};
    if (v.have_std) {
        write_stokes_image_header(
            out, {.std_includes = v.grid_covariance
                                      ? "temporal noise and the wire-grid calibration's fit error"
                                      : "temporal noise"});
        o.s0_std = &out.add_channel("S0_std");
        o.s1_std = &out.add_channel("S1_std");
        o.s2_std = &out.add_channel("S2_std");
        o.dolp_std = &out.add_channel("DoLP_std");
        o.aop_std = &out.add_channel("AoP_std");
    }
    if (options.include_slar)
        for (std::size_t k = 0; k < planes.n_angles; ++k)
            planes.slar[k] = out.add_channel("L_SLAR_" + polarizer_angle_tag(
                                                             model.positions[k].nominal_angle_deg))
                                 .data();
    return o;
}

/// Propagate: projects an unrealizable vector onto the cone (when asked), derives DoLP and AoP and,
/// with σ, their first-order uncertainties. Returns whether the measured vector was unrealizable.
bool propagate_pixel(PixelStokes& r, std::size_t i, bool project_to_realizable, OutputPlanes& o) {
    double* s = r.s;
    double pl = std::sqrt(s[1] * s[1] + s[2] * s[2]);
    const bool unrealizable = pl > s[0] && s[0] >= 0.0;
    if (unrealizable && project_to_realizable && pl > 0.0) {
        s[1] *= s[0] / pl;
        s[2] *= s[0] / pl;
        pl = s[0];
    }
    o.s0[i] = static_cast<float>(s[0]);
    o.s1[i] = static_cast<float>(s[1]);
    o.s2[i] = static_cast<float>(s[2]);
    o.dolp[i] = s[0] > 0.0 ? static_cast<float>(pl / s[0]) : kNaN;
    double psi = rad_to_deg(0.5 * std::atan2(s[2], s[1]));
    if (psi < 0.0) psi += 180.0;
    o.aop[i] = static_cast<float>(psi);
    if (!o.s0_std) return unrealizable;
    const detail::StokesStd sigma =
        detail::stokes_std(s, pl, {r.c00, r.c11, r.c22, r.c01, r.c02, r.c12});
    (*o.s0_std)[i] = sigma.s0;
    (*o.s1_std)[i] = sigma.s1;
    (*o.s2_std)[i] = sigma.s2;
    (*o.dolp_std)[i] = sigma.dolp;
    (*o.aop_std)[i] = sigma.aop_deg;
    return unrealizable;
}

}  // namespace

detail::StokesStd detail::stokes_std(const double s[3], double pl, const StokesCovariance& c) {
    StokesStd out;
    out.s0 = static_cast<float>(std::sqrt(c.c00));
    out.s1 = static_cast<float>(std::sqrt(c.c11));
    out.s2 = static_cast<float>(std::sqrt(c.c22));
    // First-order propagation to DoLP = |(S1,S2)|/S0 and AoP = ½·atan2(S2, S1): σ² = gᵀ·Cov·g.
    if (s[0] > 0.0 && pl > 0.0) {
        const double g0 = -pl / (s[0] * s[0]), g1 = s[1] / (s[0] * pl), g2 = s[2] / (s[0] * pl);
        const double var_dolp = g0 * g0 * c.c00 + g1 * g1 * c.c11 + g2 * g2 * c.c22 +
                                2.0 * (g0 * g1 * c.c01 + g0 * g2 * c.c02 + g1 * g2 * c.c12);
        const double a1 = -0.5 * s[2] / (pl * pl), a2 = 0.5 * s[1] / (pl * pl);
        const double var_aop = a1 * a1 * c.c11 + a2 * a2 * c.c22 + 2.0 * a1 * a2 * c.c12;
        out.dolp = static_cast<float>(std::sqrt(std::max(0.0, var_dolp)));
        // Where DoLP ≈ its noise the linearisation diverges; an AoP known to nothing is uniform on
        // [0°, 180°), σ = 180°/√12, the cap.
        out.aop_deg = static_cast<float>(
            std::min(kAopStdCapDeg, rad_to_deg(std::sqrt(std::max(0.0, var_aop)))));
    } else {
        out.dolp = kNaN;
        out.aop_deg = static_cast<float>(kAopStdCapDeg);
    }
    return out;
}

void detail::write_stokes_attributes(Image& out, const AnalyzerModel& model,
                                     const Eigen::Matrix3Xd& drm, const ReductionOptions& options,
                                     int unrealizable, bool wire_grid_corrected) {
    std::vector<double> angles, drm_values;
    for (const auto& p : model.positions) angles.push_back(p.nominal_angle_deg);
    write_stokes_image_header(out, {.units = options.units, .analyzer_angles_deg = angles});
    auto& a = out.attributes();
    a["units_S0"] = options.units;
    a["units_S1"] = options.units;
    a["units_S2"] = options.units;
    a["units_DoLP"] = std::string("1");
    a["units_AoP"] = std::string("deg");
    a["stokes_convention"] = std::string(
        "S1 = I0 - I90, S2 = I45 - I135; 0 deg along image rows (+x), 90 deg to the top of the "
        "image");
    for (Eigen::Index r = 0; r < 3; ++r)
        for (Eigen::Index c = 0; c < drm.cols(); ++c) drm_values.push_back(drm(r, c));
    a["drm"] = drm_values;
    a[kUnrealizablePixelsAttribute] = unrealizable;
    a[kWireGridCorrectedAttribute] = wire_grid_corrected ? 1 : 0;
}

StokesReductionRecord stokes_reduction_record(const Image& stokes) {
    const auto integer = [&](const char* name) -> std::optional<int> {
        const auto it = stokes.attributes().find(name);
        if (it == stokes.attributes().end()) return std::nullopt;
        if (!std::holds_alternative<int>(it->second))
            fail("Stokes image: attribute '{}' is not an integer", name);
        return std::get<int>(it->second);
    };
    const std::optional<int> unrealizable = integer(kUnrealizablePixelsAttribute);
    if (!unrealizable)
        fail("Stokes image: no attribute '{}' (not written by a Stokes reduction?)",
             kUnrealizablePixelsAttribute);
    StokesReductionRecord record{*unrealizable, std::nullopt};
    if (const std::optional<int> corrected = integer(kWireGridCorrectedAttribute))
        record.wire_grid_corrected = *corrected != 0;
    return record;
}

Image reduce_stokes(const std::vector<AnalyzerImage>& images, int width, int height,
                    const AnalyzerModel& model, const WireGridCalibration* wire_grid,
                    const ReductionOptions& options) {
    std::vector<AnalyzerPlanes> views;
    views.reserve(images.size());
    for (const AnalyzerImage& im : images)
        views.push_back({im.angle_deg, im.signal, im.signal_std, im.source});
    return reduce_stokes(views, width, height, model, wire_grid, options);
}

Image reduce_stokes(const std::vector<AnalyzerPlanes>& images, int width, int height,
                    const AnalyzerModel& model, const WireGridCalibration* wire_grid,
                    const ReductionOptions& options) {
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    const Eigen::Matrix3Xd drm = model.data_reduction_matrix();
    const ValidatedInputs inputs = validate(images, width, height, model, wire_grid);

    Image out(width, height);
    AnglePlanes planes(inputs, model, drm);
    OutputPlanes outputs = add_output_channels(out, inputs, model, options, planes);
    int unrealizable = 0;
    const auto row = static_cast<std::size_t>(width);
    for (std::size_t start = 0; start < n; start += row) {
        throw_if_cancelled(options.cancel, "Stokes reduction");  // once per row, not per pixel
        for (std::size_t i = start; i < start + row; ++i) {
            PixelStokes pixel = solve_pixel(planes, i, inputs.have_std);
            if (propagate_pixel(pixel, i, options.project_to_realizable, outputs)) ++unrealizable;
        }
    }
    detail::write_stokes_attributes(out, model, drm, options, unrealizable, wire_grid != nullptr);
    return out;
}

}  // namespace tirpol::calibration
