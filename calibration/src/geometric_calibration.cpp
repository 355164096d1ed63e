#include "tirpol/calibration/geometric_calibration.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>

#include "tirpol/core/error.h"

namespace tirpol::calibration {

namespace {
std::vector<cv::Point3f> cv_object_points(const CalibrationTarget& target) {
    std::vector<cv::Point3f> out;
    for (const Vec3& p : target.object_points())
        out.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()),
                         static_cast<float>(p.z()));
    return out;
}

std::vector<cv::Point2f> cv_points(const TargetView& view) {
    std::vector<cv::Point2f> out;
    for (const Vec2& p : view.points_px)
        out.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
    return out;
}

/// Target-plane normal in camera coordinates from the view's homography and a nominal camera
/// (f = image width, centred principal point). Views with the same target orientation give the same
/// normal whatever the true intrinsics, since K_nominal⁻¹·K keeps equal columns equal.
Vec3 nominal_normal(const std::vector<cv::Point3f>& object, const std::vector<cv::Point2f>& image,
                    int width, int height) {
    std::vector<cv::Point2f> plane;
    for (const auto& p : object) plane.emplace_back(p.x, p.y);
    const cv::Mat h = cv::findHomography(plane, image);
    if (h.empty()) return Vec3::Zero();
    const double f = width, cx = 0.5 * width, cy = 0.5 * height;
    auto column = [&](int c) {
        return Vec3((h.at<double>(0, c) - cx * h.at<double>(2, c)) / f,
                    (h.at<double>(1, c) - cy * h.at<double>(2, c)) / f, h.at<double>(2, c));
    };
    const Vec3 n = column(0).normalized().cross(column(1).normalized());
    return n.norm() > 0.0 ? Vec3(n.normalized()) : Vec3::Zero();
}

void check_not_degenerate(const std::vector<cv::Point3f>& object,
                          const std::vector<std::vector<cv::Point2f>>& image, int width, int height,
                          double min_spread_deg) {
    std::vector<Vec3> normals;
    for (const auto& view : image) normals.push_back(nominal_normal(object, view, width, height));
    double spread = 0.0;
    for (std::size_t i = 0; i < normals.size(); ++i)
        for (std::size_t j = i + 1; j < normals.size(); ++j)
            spread = std::max(
                spread,
                rad_to_deg(std::acos(std::clamp(std::abs(normals[i].dot(normals[j])), 0.0, 1.0))));
    if (spread < min_spread_deg)
        fail(
            "degenerate views: the target plane has the same orientation in all {} views (largest "
            "angle between "
            "them {:.1f}°, need ≥ {:.0f}°); the focal length cannot be separated from the "
            "distance. Tilt the "
            "target by 20–45° about different axes between views",
            image.size(), spread, min_spread_deg);
}

int opencv_flags(const GeometricCalibrationOptions& o) {
    const std::size_t n = distortion_length(o.distortion_model);
    int flags = 0;
    if (n >= 8) flags |= cv::CALIB_RATIONAL_MODEL;
    if (n >= 12) flags |= cv::CALIB_THIN_PRISM_MODEL;
    if (o.fix_k3) flags |= cv::CALIB_FIX_K3;
    if (o.zero_tangential) flags |= cv::CALIB_ZERO_TANGENT_DIST;
    return flags;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty()      ? 0.0
           : v.size() % 2 ? v[v.size() / 2]
                          : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}
}  // namespace

GeometricCalibrationResult calibrate_geometric(const std::vector<TargetView>& views,
                                               const CalibrationTarget& target, int width,
                                               int height,
                                               const GeometricCalibrationOptions& options) {
    const std::size_t n_dist = distortion_length(options.distortion_model);
    if (width < 8 || height < 8)
        fail("geometric calibration: image size {}x{} is too small", width, height);
    const std::size_t min_views = static_cast<std::size_t>(std::max(options.min_views, 3));
    if (views.size() < min_views)
        fail(
            "geometric calibration: {} view(s) of the target, need at least {} (10–20 recommended, "
            "docs/camera-geometry.md)",
            views.size(), min_views);
    const auto object = cv_object_points(target);
    std::vector<std::vector<cv::Point3f>> object_points;
    std::vector<std::vector<cv::Point2f>> image_points;
    for (const auto& v : views) {
        if (v.points_px.size() != object.size())
            fail("geometric calibration: view '{}' has {} points, the target {} has {}", v.name,
                 v.points_px.size(), target.to_string(), object.size());
        object_points.push_back(object);
        image_points.push_back(cv_points(v));
    }
    check_not_degenerate(object, image_points, width, height, options.min_tilt_spread_deg);

    cv::Mat camera_matrix = cv::Mat::eye(3, 3, CV_64F),
            dist = cv::Mat::zeros(static_cast<int>(n_dist), 1, CV_64F);
    std::vector<cv::Mat> rvecs, tvecs;
    cv::Mat std_intrinsics, std_extrinsics, per_view;
    const double rms = cv::calibrateCamera(
        object_points, image_points, cv::Size(width, height), camera_matrix, dist, rvecs, tvecs,
        std_intrinsics, std_extrinsics, per_view, opencv_flags(options),
        cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 200, 1e-12));
    if (!std::isfinite(rms) || !cv::checkRange(camera_matrix) || !cv::checkRange(dist))
        fail(
            "geometric calibration did not converge (RMS {}); check the target size and that views "
            "cover the image",
            rms);

    GeometricCalibrationResult result;
    CameraModel& m = result.model;
    m.width = width;
    m.height = height;
    m.fx = camera_matrix.at<double>(0, 0);
    m.fy = camera_matrix.at<double>(1, 1);
    m.cx = camera_matrix.at<double>(0, 2);
    m.cy = camera_matrix.at<double>(1, 2);
    m.distortion.assign(dist.begin<double>(),
                        dist.begin<double>() + static_cast<std::ptrdiff_t>(n_dist));
    m.rms_px = rms;
    m.views = static_cast<int>(views.size());
    m.target = target.to_string();
    // OpenCV's std_intrinsics order: fx fy cx cy k1 k2 p1 p2 k3 k4 k5 k6 s1 s2 s3 s4 τx τy.
    result.parameter_names = {"fx", "fy", "cx", "cy"};
    const char* dist_names[] = {"k1", "k2", "p1", "p2", "k3", "k4",
                                "k5", "k6", "s1", "s2", "s3", "s4"};
    for (std::size_t i = 0; i < n_dist; ++i) result.parameter_names.emplace_back(dist_names[i]);
    for (std::size_t i = 0; i < 4 + n_dist; ++i)
        m.std_dev.push_back(std_intrinsics.at<double>(static_cast<int>(i)));

    std::vector<double> view_rms;
    for (std::size_t i = 0; i < views.size(); ++i)
        view_rms.push_back(per_view.at<double>(static_cast<int>(i)));
    const double med = median(view_rms);
    const double threshold =
        std::max(options.outlier_factor * med, med + options.outlier_margin_px);
    for (std::size_t i = 0; i < views.size(); ++i) {
        cv::Mat r;
        cv::Rodrigues(rvecs[i], r);
        const double tilt =
            rad_to_deg(std::acos(std::clamp(std::abs(r.at<double>(2, 2)), 0.0, 1.0)));
        result.views.push_back({views[i].name, view_rms[i], tilt, view_rms[i] > threshold});
    }
    return result;
}

GeometricCalibrationResult calibrate_geometric_frames(
    const std::vector<std::filesystem::path>& frames, const CalibrationTarget& target,
    const GeometricCalibrationOptions& options) {
    if (frames.empty()) fail("geometric calibration: no frames given");
    std::vector<std::vector<float>> planes;
    std::vector<std::string> names;
    int width = 0, height = 0;
    for (const auto& path : frames) {
        Image frame = read_calibration_frame(path);
        if (width == 0) {
            width = frame.width();
            height = frame.height();
        } else if (frame.width() != width || frame.height() != height) {
            fail(
                "{}: frame is {}x{}, the first frame {} is {}x{}; all frames must come from one "
                "camera mode",
                path.string(), frame.width(), frame.height(), frames.front().string(), width,
                height);
        }
        planes.push_back(std::move(frame.channel("counts")));
        names.push_back(path.string());
    }
    std::vector<TargetView> views;
    std::vector<std::string> missing, why_missing;
    auto searches = search_target_views(planes, width, height, target, names);
    for (std::size_t i = 0; i < searches.size(); ++i) {
        if (searches[i].view) {
            views.push_back(std::move(*searches[i].view));
        } else {
            missing.push_back(names[i]);
            why_missing.push_back(std::move(searches[i].failure));
        }
    }
    const std::size_t min_views = static_cast<std::size_t>(std::max(options.min_views, 3));
    if (views.size() < min_views) {
        std::string list;
        for (std::size_t i = 0; i < missing.size(); ++i)
            list += fmt::format("\n  {}: {}", missing[i], why_missing[i]);
        fail(
            "geometric calibration: target {} found in {} of {} frames, need at least {}; not "
            "found in:{}",
            target.to_string(), views.size(), frames.size(), min_views, list);
    }
    GeometricCalibrationResult result = calibrate_geometric(views, target, width, height, options);
    result.frames_without_target = std::move(missing);
    result.why_target_not_found = std::move(why_missing);
    return result;
}

}  // namespace tirpol::calibration
