#include "tirpol/calibration/analyzer.h"

#include <Eigen/Dense>
#include <cmath>
#include <limits>

#include "tirpol/core/error.h"
#include "tirpol/core/geometry.h"

namespace tirpol::calibration {

double AnalyzerPosition::extinction_ratio() const {
    return diattenuation >= 1.0 ? std::numeric_limits<double>::infinity()
                                : (1.0 + diattenuation) / (1.0 - diattenuation);
}

Eigen::RowVector3d AnalyzerPosition::row() const {
    const double two_theta = 2.0 * deg_to_rad(axis_angle_deg);
    return {0.5, 0.5 * diattenuation * std::cos(two_theta),
            0.5 * diattenuation * std::sin(two_theta)};
}

AnalyzerModel AnalyzerModel::ideal(const std::vector<double>& angles_deg) {
    AnalyzerModel m;
    for (double a : angles_deg) m.positions.push_back({a, a, 1.0, 1.0, 0.0});
    return m;
}

AnalyzerModel AnalyzerModel::non_ideal(const std::vector<double>& angles_deg,
                                       double extinction_ratio, double angle_offset_deg,
                                       double t_max) {
    if (!(extinction_ratio >= 1.0)) fail("extinction ratio {}; expected ≥ 1", extinction_ratio);
    const double d = (extinction_ratio - 1.0) / (extinction_ratio + 1.0);
    const double t_min = t_max / extinction_ratio;
    AnalyzerModel m;
    for (double a : angles_deg)
        m.positions.push_back({a, a + angle_offset_deg, d, t_max + t_min, 0.0});
    return m;
}

Eigen::MatrixX3d AnalyzerModel::measurement_matrix() const {
    Eigen::MatrixX3d w(static_cast<Eigen::Index>(positions.size()), 3);
    for (std::size_t k = 0; k < positions.size(); ++k)
        w.row(static_cast<Eigen::Index>(k)) = positions[k].row();
    return w;
}

namespace {
std::string angle_list(const AnalyzerModel& m) {
    std::string s;
    for (const auto& p : m.positions)
        s += (s.empty() ? "" : ", ") + fmt::format("{:g}°", p.nominal_angle_deg);
    return s;
}
}  // namespace

Eigen::Matrix3Xd AnalyzerModel::data_reduction_matrix() const {
    if (positions.size() < 3)
        fail("analyzer has {} position(s) ({}); linear Stokes reduction needs at least 3 angles",
             positions.size(), angle_list(*this));
    const Eigen::MatrixX3d w = measurement_matrix();
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(w);
    const auto& sv = svd.singularValues();
    if (!(sv[2] > 1e-6 * sv[0]))
        fail(
            "analyzer angles ({}) do not determine S0, S1 and S2 (the measurement matrix is "
            "singular); use at least "
            "3 distinct angles modulo 180°",
            angle_list(*this));
    return w.completeOrthogonalDecomposition().pseudoInverse();
}

double AnalyzerModel::condition_number() const {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(measurement_matrix());
    const auto& sv = svd.singularValues();
    return sv[0] / sv[sv.size() - 1];
}

AnalyzerModel estimate_analyzer(const std::vector<double>& nominal_angles_deg,
                                const std::vector<KnownSourceMeasurement>& measurements) {
    const std::size_t n_angles = nominal_angles_deg.size();
    const std::size_t m = measurements.size();
    if (m < 4)
        fail(
            "analyzer calibration has {} known-source measurement(s); expected at least 4 (two "
            "source intensities "
            "and two polarization orientations)",
            m);
    Eigen::MatrixXd a(static_cast<Eigen::Index>(m), 4);
    for (std::size_t j = 0; j < m; ++j) {
        const auto& meas = measurements[j];
        if (meas.intensities.size() != n_angles)
            fail(
                "known-source measurement {} has {} intensities; expected one per analyzer angle "
                "({})",
                j, meas.intensities.size(), n_angles);
        for (double v : meas.intensities)
            if (!std::isfinite(v))
                fail("known-source measurement {}: intensity is NaN or infinite", j);
        a.row(static_cast<Eigen::Index>(j)) << meas.source_stokes[0], meas.source_stokes[1],
            meas.source_stokes[2], 1.0;
    }
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
    if (qr.rank() < 4)
        fail(
            "the known sources do not span (S0, S1, S2, offset): rank {} of 4; measure at least "
            "two source "
            "intensities and two polarization orientations 45° apart",
            qr.rank());
    AnalyzerModel model;
    for (std::size_t k = 0; k < n_angles; ++k) {
        Eigen::VectorXd y(static_cast<Eigen::Index>(m));
        for (std::size_t j = 0; j < m; ++j)
            y[static_cast<Eigen::Index>(j)] = measurements[j].intensities[k];
        const Eigen::Vector4d w = qr.solve(y);
        AnalyzerPosition p;
        p.nominal_angle_deg = nominal_angles_deg[k];
        p.relative_transmission = 2.0 * w[0];
        p.diattenuation = std::min(1.0, std::hypot(w[1], w[2]) / w[0]);
        // The fitted axis angle is defined modulo 180°: take the branch nearest the nominal angle.
        double theta = rad_to_deg(0.5 * std::atan2(w[2], w[1]));
        theta += 180.0 * std::round((nominal_angles_deg[k] - theta) / 180.0);
        p.axis_angle_deg = theta;
        p.background = w[3];
        model.positions.push_back(p);
    }
    return model;
}

}  // namespace tirpol::calibration
