#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>

#include "tirpol/calibration/stokes_reduction.h"
#include "tirpol/core/error.h"
#include "tirpol/core/stokes.h"
#include "validate.h"

namespace tirpol::calibration {

const WireGridPosition& WireGridCalibration::at(double angle_deg) const {
    for (const auto& p : positions)
        if (same_polarizer_angle(p.angle_deg, angle_deg)) return p;
    std::string present;
    for (const auto& p : positions)
        present += (present.empty() ? "" : ", ") + fmt::format("{:g}°", p.angle_deg);
    fail("wire-grid calibration has no analyzer angle {:g}°; it has {}", angle_deg,
         present.empty() ? "none" : present);
}

WireGridCalibration fit_wire_grid(const std::vector<PolarizedBlackbodyFrame>& frames, int width,
                                  int height, const Band& band) {
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    // Group by angle (rounded to 0.01° so that repeated frames at one angle meet).
    std::map<long, std::vector<const PolarizedBlackbodyFrame*>> by_angle;
    for (const auto& f : frames) {
        detail::check_plane(f.signal, n, f.source, width, height);
        if (!(f.temperature_k > 0.0))
            fail("{}: blackbody temperature {} K; expected > 0 K", f.source, f.temperature_k);
        if (!f.signal_std.empty())
            detail::check_std_plane(f.signal_std, n, f.source + " (std)", width, height);
        by_angle[polarizer_angle_key(f.angle_deg)].push_back(&f);
    }
    const bool with_covariance = std::all_of(frames.begin(), frames.end(),
                                             [](const auto& f) { return !f.signal_std.empty(); });
    if (by_angle.empty())
        fail("wire-grid calibration: no blackbody frames taken through the polarizer");
    WireGridCalibration cal;
    cal.width = width;
    cal.height = height;
    for (const auto& [key, group] : by_angle) {
        const double angle = polarizer_angle_deg(key);
        std::vector<double> temps;
        for (const auto* f : group)
            if (std::none_of(temps.begin(), temps.end(),
                             [&](double t) { return std::abs(t - f->temperature_k) < 1e-3; }))
                temps.push_back(f->temperature_k);
        if (temps.size() < 2)
            fail(
                "analyzer angle {:g}°: blackbody frames at {} distinct temperature(s) ({:g} K); τ "
                "and B need at least 2",
                angle, temps.size(), temps.front());
        const auto k = static_cast<Eigen::Index>(group.size());
        Eigen::MatrixXd a(k, 2);
        for (Eigen::Index j = 0; j < k; ++j)
            a.row(j) << 0.5 * band.radiance(group[static_cast<std::size_t>(j)]->temperature_k), 1.0;
        const Eigen::MatrixXd projector = a.completeOrthogonalDecomposition().pseudoInverse();
        WireGridPosition pos;
        pos.angle_deg = angle;
        pos.tau.resize(n);
        pos.background.resize(n);
        pos.residual_rms.resize(n);
        if (with_covariance) {
            pos.tau_var.resize(n);
            pos.background_var.resize(n);
            pos.tau_background_cov.resize(n);
        }
        Eigen::VectorXd y(k);
        for (std::size_t i = 0; i < n; ++i) {
            for (Eigen::Index j = 0; j < k; ++j)
                y[j] = group[static_cast<std::size_t>(j)]->signal[i];
            const Eigen::Vector2d c = projector * y;
            pos.tau[i] = static_cast<float>(c[0]);
            pos.background[i] = static_cast<float>(c[1]);
            pos.residual_rms[i] =
                static_cast<float>(std::sqrt((y - a * c).squaredNorm() / static_cast<double>(k)));
            if (!with_covariance) continue;
            Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
            for (Eigen::Index j = 0; j < k; ++j) {
                const double s = group[static_cast<std::size_t>(j)]->signal_std[i];
                cov += s * s * projector.col(j) * projector.col(j).transpose();
            }
            pos.tau_var[i] = static_cast<float>(cov(0, 0));
            pos.background_var[i] = static_cast<float>(cov(1, 1));
            pos.tau_background_cov[i] = static_cast<float>(cov(0, 1));
        }
        cal.positions.push_back(std::move(pos));
    }
    return cal;
}

double wire_grid_background(double grid_reflectance, double sky_radiance_w_m2_sr,
                            double grid_emissivity, double grid_temperature_k, const Band& band) {
    if (grid_reflectance < 0.0 || grid_emissivity < 0.0 || grid_reflectance + grid_emissivity > 1.0)
        fail("wire grid reflectance {} and emissivity {}: expected both ≥ 0 with a sum ≤ 1",
             grid_reflectance, grid_emissivity);
    return grid_reflectance * sky_radiance_w_m2_sr +
           grid_emissivity * band.radiance(grid_temperature_k);
}

}  // namespace tirpol::calibration
