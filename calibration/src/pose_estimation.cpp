#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <fstream>
#include <opencv2/calib3d.hpp>
#include <sstream>

#include "tirpol/calibration/geometric_calibration.h"
#include "tirpol/core/error.h"
#include "tirpol/core/output_guard.h"

namespace tirpol::calibration {

std::vector<ControlPoint> read_control_points(const std::filesystem::path& path) {
    check_input_file(path);
    std::ifstream in(path);
    if (!in) fail("{}: cannot open the control-point file", path.string());
    std::vector<ControlPoint> points;
    std::string line;
    int line_no = 0;
    bool header_seen = false;
    while (std::getline(in, line)) {
        ++line_no;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty() || line[0] == '#') continue;
        std::vector<std::string> cells;
        std::stringstream ss(line);
        for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
        if (!header_seen) {
            if (line != "name,x_m,y_m,z_m,u_px,v_px")
                fail("{}:{}: expected the header name,x_m,y_m,z_m,u_px,v_px, got '{}'",
                     path.string(), line_no, line);
            header_seen = true;
            continue;
        }
        if (cells.size() != 6)
            fail("{}:{}: expected 6 columns (name,x_m,y_m,z_m,u_px,v_px), got {}", path.string(),
                 line_no, cells.size());
        static const char* columns[] = {"name", "x_m", "y_m", "z_m", "u_px", "v_px"};
        double v[5];
        for (int i = 0; i < 5; ++i) {
            std::size_t used = 0;
            try {
                v[i] = std::stod(cells[static_cast<std::size_t>(i + 1)], &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (used == 0 || !std::isfinite(v[i]))
                fail("{}:{}: column {} '{}' is not a number", path.string(), line_no,
                     columns[i + 1], cells[static_cast<std::size_t>(i + 1)]);
        }
        points.push_back({cells[0], Vec3(v[0], v[1], v[2]), Vec2(v[3], v[4])});
    }
    if (!header_seen)
        fail("{}: empty control-point file (expected the header name,x_m,y_m,z_m,u_px,v_px)",
             path.string());
    return points;
}

namespace {
/// Eigenvalues (ascending) of the scatter matrix of the points' world positions.
Eigen::Vector3d scatter_eigenvalues(const std::vector<ControlPoint>& points) {
    Vec3 mean = Vec3::Zero();
    for (const auto& p : points) mean += p.world_m;
    mean /= static_cast<double>(points.size());
    Mat3 scatter = Mat3::Zero();
    for (const auto& p : points) scatter += (p.world_m - mean) * (p.world_m - mean).transpose();
    return Eigen::SelfAdjointEigenSolver<Mat3>(scatter).eigenvalues();
}

/// True when the points lie on a plane to within 1 % of their extent (a wall, a rack of panels).
bool coplanar(const std::vector<ControlPoint>& points) {
    const Eigen::Vector3d ev = scatter_eigenvalues(points);
    return ev[0] < 1e-4 * ev[2];
}

void check_input(const CameraModel& model, const std::vector<ControlPoint>& points) {
    validate_camera_model(model, "camera model");
    if (points.size() < 4)
        fail("pose: {} control point(s), need at least 4 (6 or more, spread in depth, recommended)",
             points.size());
    for (const auto& p : points)
        if (p.pixel.x() < -0.5 || p.pixel.y() < -0.5 || p.pixel.x() > model.width - 0.5 ||
            p.pixel.y() > model.height - 0.5)
            fail("pose: control point '{}' at pixel ({}, {}) is outside the {}x{} image", p.name,
                 p.pixel.x(), p.pixel.y(), model.width, model.height);
    // Collinear (or coincident) world points leave a rotation about their line free.
    const Eigen::Vector3d ev = scatter_eigenvalues(points);
    if (ev[2] <= 0.0 || ev[1] < 1e-6 * ev[2])
        fail(
            "pose: the {} control points are collinear or coincident in the world; survey points "
            "spread over an area",
            points.size());
}

cv::Mat camera_matrix(const CameraModel& m) {
    return (cv::Mat_<double>(3, 3) << m.fx, 0, m.cx, 0, m.fy, m.cy, 0, 0, 1);
}
}  // namespace

PoseResult estimate_pose(const CameraModel& model, const std::vector<ControlPoint>& points,
                         const PoseOptions& options) {
    check_input(model, points);
    std::vector<cv::Point3d> world;
    std::vector<cv::Point2d> pixels;
    for (const auto& p : points) {
        world.emplace_back(p.world_m.x(), p.world_m.y(), p.world_m.z());
        pixels.emplace_back(p.pixel.x(), p.pixel.y());
    }
    const cv::Mat k = camera_matrix(model), dist(model.distortion, true);
    cv::Mat rvec, tvec;
    std::vector<int> inlier_index;
    // EPnP's minimal sets of (nearly) coplanar points are degenerate and can return the mirrored
    // pose; IPPE (Collins & Bartoli, IJCV 109(3), 2014) is the planar solver.
    const int method = points.size() == 4 ? cv::SOLVEPNP_AP3P
                       : coplanar(points) ? cv::SOLVEPNP_IPPE
                                          : cv::SOLVEPNP_EPNP;
    const bool ok = cv::solvePnPRansac(world, pixels, k, dist, rvec, tvec, false, 1000,
                                       static_cast<float>(options.ransac_threshold_px), 0.999,
                                       inlier_index, method);
    if (!ok || inlier_index.size() < 4)
        fail(
            "pose: no pose explains at least 4 of the {} control points within {} px; check the "
            "pixel picks and that "
            "the points are in the scene's world frame",
            points.size(), options.ransac_threshold_px);
    std::vector<cv::Point3d> world_in;
    std::vector<cv::Point2d> pixels_in;
    for (int i : inlier_index) {
        world_in.push_back(world[static_cast<std::size_t>(i)]);
        pixels_in.push_back(pixels[static_cast<std::size_t>(i)]);
    }
    cv::solvePnPRefineLM(
        world_in, pixels_in, k, dist, rvec, tvec,
        cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 100, 1e-12));

    PoseResult result;
    cv::Mat r;
    cv::Rodrigues(rvec, r);
    CameraPose& pose = result.pose;
    for (int i = 0; i < 3; ++i) {
        pose.translation_m[i] = tvec.at<double>(i);
        for (int j = 0; j < 3; ++j) pose.camera_from_world(i, j) = r.at<double>(i, j);
    }
    std::string behind;
    for (const auto& p : points)
        if ((pose.camera_from_world * p.world_m + pose.translation_m).z() <= 0.0)
            behind += " '" + p.name + "'";
    if (!behind.empty())
        fail(
            "pose: the best pose puts control point(s){} on or behind the camera; check their "
            "world coordinates "
            "(scene frame, z up) and pixel picks",
            behind);

    std::vector<cv::Point2d> projected;
    cv::projectPoints(world, rvec, tvec, k, dist, projected);
    result.inlier.assign(points.size(), false);
    for (int i : inlier_index) result.inlier[static_cast<std::size_t>(i)] = true;
    double sum2 = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        result.residual_px.push_back(cv::norm(projected[i] - pixels[i]));
        if (result.inlier[i]) sum2 += result.residual_px[i] * result.residual_px[i];
    }
    const auto n = static_cast<double>(inlier_index.size());
    pose.points = static_cast<int>(inlier_index.size());
    pose.rms_px = std::sqrt(sum2 / n);

    // 1σ from the Jacobian of the inliers' reprojections with respect to (rvec, tvec).
    std::vector<cv::Point2d> unused;
    cv::Mat jacobian;
    cv::projectPoints(world_in, rvec, tvec, k, dist, unused, jacobian);
    Eigen::Matrix<double, Eigen::Dynamic, 6> j(jacobian.rows, 6);
    for (int row = 0; row < jacobian.rows; ++row)
        for (int c = 0; c < 6; ++c) j(row, c) = jacobian.at<double>(row, c);
    const double dof = 2.0 * n - 6.0;
    const double sigma2 = dof > 0.0 ? sum2 / dof : 0.0;
    const Eigen::Matrix<double, 6, 6> cov = sigma2 * (j.transpose() * j).inverse();
    // A small rvec perturbation is (to first order) a rotation about the camera axes.
    for (int i = 0; i < 3; ++i)
        pose.rotation_sigma_deg[i] = rad_to_deg(std::sqrt(std::max(cov(i, i), 0.0)));
    // Camera centre C = −Rᵀt: propagate through a numeric Jacobian dC/d(rvec, t).
    auto centre = [&](const Eigen::Matrix<double, 6, 1>& x) {
        cv::Mat rv = (cv::Mat_<double>(3, 1) << x[0], x[1], x[2]), rr;
        cv::Rodrigues(rv, rr);
        Mat3 rm;
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) rm(a, b) = rr.at<double>(a, b);
        return Vec3(-rm.transpose() * Vec3(x[3], x[4], x[5]));
    };
    Eigen::Matrix<double, 6, 1> x0;
    x0 << rvec.at<double>(0), rvec.at<double>(1), rvec.at<double>(2), tvec.at<double>(0),
        tvec.at<double>(1), tvec.at<double>(2);
    Eigen::Matrix<double, 3, 6> dc;
    for (int c = 0; c < 6; ++c) {
        Eigen::Matrix<double, 6, 1> dx = Eigen::Matrix<double, 6, 1>::Zero();
        dx[c] = 1e-7;
        dc.col(c) = (centre(x0 + dx) - centre(x0 - dx)) / 2e-7;
    }
    const Mat3 cov_c = dc * cov * dc.transpose();
    for (int i = 0; i < 3; ++i) pose.position_sigma_m[i] = std::sqrt(std::max(cov_c(i, i), 0.0));
    return result;
}

}  // namespace tirpol::calibration
