#include "tirpol/core/camera_model.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>

#include "tirpol/core/atomic_file.h"
#include "tirpol/core/config.h"
#include "tirpol/core/error.h"

namespace tirpol {

std::size_t distortion_length(const std::string& model) {
    if (model == "standard") return 5;
    if (model == "rational") return 8;
    if (model == "thin_prism") return 12;
    fail(
        "distortion model '{}': expected standard (k1 k2 p1 p2 k3), rational (+ k4 k5 k6) or "
        "thin_prism (+ s1..s4)",
        model);
}

std::string distortion_model_of_length(std::size_t length) {
    switch (length) {
        case 5:
            return "standard";
        case 8:
            return "rational";
        case 12:
            return "thin_prism";
        default:
            fail(
                "{} distortion coefficients: expected 5 (standard), 8 (rational) or 12 "
                "(thin_prism)",
                length);
    }
}

namespace {
double coefficient(const std::vector<double>& d, std::size_t i) {
    return i < d.size() ? d[i] : 0.0;
}

struct DistortionTerms {
    double radial;  ///< (1 + k1 r² + k2 r⁴ + k3 r⁶) / (1 + k4 r² + k5 r⁴ + k6 r⁶)
    Vec2 additive;  ///< tangential (p1, p2) and thin-prism (s1..s4) terms
};

DistortionTerms distortion_terms(const std::vector<double>& d, const Vec2& p) {
    const double x = p.x(), y = p.y(), r2 = x * x + y * y, r4 = r2 * r2, r6 = r4 * r2;
    const double k1 = coefficient(d, 0), k2 = coefficient(d, 1), p1 = coefficient(d, 2),
                 p2 = coefficient(d, 3), k3 = coefficient(d, 4), k4 = coefficient(d, 5),
                 k5 = coefficient(d, 6), k6 = coefficient(d, 7), s1 = coefficient(d, 8),
                 s2 = coefficient(d, 9), s3 = coefficient(d, 10), s4 = coefficient(d, 11);
    return {(1.0 + k1 * r2 + k2 * r4 + k3 * r6) / (1.0 + k4 * r2 + k5 * r4 + k6 * r6),
            Vec2(2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x) + s1 * r2 + s2 * r4,
                 p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y + s3 * r2 + s4 * r4)};
}

/// OpenCV's forward distortion of normalised coordinates (calib3d, "Detailed description").
Vec2 distort_normalised(const std::vector<double>& d, const Vec2& p) {
    const DistortionTerms t = distortion_terms(d, p);
    return t.radial * p + t.additive;
}
}  // namespace

Vec2 CameraModel::project(const Vec3& point_camera) const {
    const Vec2 d = distort_normalised(
        distortion, Vec2(point_camera.x() / point_camera.z(), point_camera.y() / point_camera.z()));
    return {fx * d.x() + cx, fy * d.y() + cy};
}

Vec2 CameraModel::undistort_distorted(const Vec2& goal) const {
    // Fixed-point iteration (as cv::undistortPoints) gets close; Newton on the forward model then
    // makes it exact where fixed-point converges slowly (strong barrel distortion at the corners).
    Vec2 p = goal;
    for (int i = 0; i < 10; ++i) {
        const DistortionTerms t = distortion_terms(distortion, p);
        const Vec2 next = (goal - t.additive) / t.radial;
        if (!next.allFinite()) break;
        p = next;
    }
    for (int i = 0; i < 20; ++i) {
        const Vec2 residual = distort_normalised(distortion, p) - goal;
        if (residual.norm() < 1e-15) break;
        constexpr double h = 1e-7;
        Eigen::Matrix2d jacobian;
        jacobian.col(0) = (distort_normalised(distortion, p + Vec2(h, 0)) -
                           distort_normalised(distortion, p - Vec2(h, 0))) /
                          (2 * h);
        jacobian.col(1) = (distort_normalised(distortion, p + Vec2(0, h)) -
                           distort_normalised(distortion, p - Vec2(0, h))) /
                          (2 * h);
        p -= jacobian.inverse() * residual;
    }
    return p;
}

void validate_camera_model(const CameraModel& m, const std::string& where) {
    if (m.width < 1 || m.height < 1)
        fail("{}: image_width/image_height must be positive, got {}x{}", where, m.width, m.height);
    if (!(m.fx > 0.0 && m.fy > 0.0 && std::isfinite(m.fx) && std::isfinite(m.fy)))
        fail("{}: camera_matrix focal lengths fx, fy must be positive, got {} {}", where, m.fx,
             m.fy);
    if (!std::isfinite(m.cx) || !std::isfinite(m.cy))
        fail("{}: camera_matrix principal point is not finite", where);
    try {
        (void)distortion_model_of_length(m.distortion.size());
    } catch (const Error& e) {
        fail("{}: distortion_coefficients: {}", where, e.what());
    }
    for (double c : m.distortion)
        if (!std::isfinite(c))
            fail("{}: distortion_coefficients contain a non-finite value", where);
}

namespace {
// Reading: yaml-cpp through ConfigNode (errors with file, line and field), not cv::FileStorage,
// whose YAML parser has looped for ever on malformed text (a '%' followed by '--' or '---', fuzz
// regressions camera_geometry/percent_*). The files stay OpenCV's layout, written by
// cv::FileStorage below: a `%YAML:1.0` first line and `!!opencv-matrix` maps of rows, cols, dt,
// data.

// OpenCV writes its directive as `%YAML:1.0`, which is not YAML 1.x syntax (`%YAML 1.0`); it is
// the only directive OpenCV writes and carries nothing, so the first line is blanked (line numbers
// in messages stay those of the file). Any other '%' is yaml-cpp's to judge.
ConfigNode parse_opencv_yaml(const std::filesystem::path& path) {
    std::string text = read_file(path);
    if (text.rfind("%YAML:", 0) == 0) text.replace(0, std::min(text.find('\n'), text.size()), "");
    const ConfigNode root = ConfigNode::parse(text, path.string());
    if (!root.is_map())
        fail("{}: expected a camera file: a YAML mapping of named fields", path.string());
    return root;
}

// An OpenCV matrix (`!!opencv-matrix`: rows, cols, dt, data in row-major order) of `rows`×`cols`
// (any shape when rows is 0), as a row-major vector.
std::vector<double> required_matrix(const ConfigNode& root, const char* key, int rows, int cols) {
    const ConfigNode n = root.at(key);
    if (!n.is_map())
        n.fail(
            "expected an OpenCV matrix (!!opencv-matrix with integer rows, cols and a data list)");
    n.check_keys({"rows", "cols", "dt", "data"});
    const int r = n.get<int>("rows"), c = n.get<int>("cols");
    const std::string dt = n.get_or<std::string>("dt", "d");
    if (dt != "d" && dt != "f" && dt != "i")
        n.at("dt").fail("expected an element type d (double), f (float) or i (int), got '" + dt +
                        "'");
    const ConfigNode data = n.at("data");
    if (!data.is_sequence()) data.fail("expected a list of numbers");
    const std::size_t count = data.elements().size();
    if (r < 1 || c < 1 || static_cast<long long>(r) * c != static_cast<long long>(count))
        n.fail(fmt::format("declares {}x{} values but its data holds {}", r, c, count));
    if (rows > 0 && (r != rows || c != cols))
        n.fail(fmt::format("must be {}x{}, got {}x{}", rows, cols, r, c));
    return data.as<std::vector<double>>();
}

int required_int(const ConfigNode& root, const char* key) { return root.get<int>(key); }

double optional_real(const ConfigNode& root, const char* key) {
    return root.get_or<double>(key, 0.0);
}

void commit_storage(cv::FileStorage& fs, const std::filesystem::path& path) {
    write_file_atomic(path, fs.releaseAndGetString());
}
}  // namespace

CameraModel read_camera_model(const std::filesystem::path& path) {
    const ConfigNode fs = parse_opencv_yaml(path);
    CameraModel m;
    m.width = required_int(fs, "image_width");
    m.height = required_int(fs, "image_height");
    const std::vector<double> k = required_matrix(fs, "camera_matrix", 3, 3);
    if (k[1] != 0.0 || k[3] != 0.0 || k[6] != 0.0 || k[7] != 0.0 || k[8] != 1.0)
        fs.at("camera_matrix").fail("must be [fx 0 cx; 0 fy cy; 0 0 1] (no skew)");
    m.fx = k[0];
    m.fy = k[4];
    m.cx = k[2];
    m.cy = k[5];
    m.distortion = required_matrix(fs, "distortion_coefficients", 0, 0);
    if (fs.has("distortion_model")) {
        const std::string declared = fs.get<std::string>("distortion_model");
        if (distortion_length(declared) != m.distortion.size())
            fail("{}: distortion_model '{}' needs {} coefficients, distortion_coefficients has {}",
                 path.string(), declared, distortion_length(declared), m.distortion.size());
    }
    m.rms_px = optional_real(fs, "rms_reprojection_error_px");
    m.views = fs.get_or<int>("views", 0);
    if (fs.has("std_dev_intrinsics")) m.std_dev = required_matrix(fs, "std_dev_intrinsics", 0, 0);
    m.target = fs.get_or<std::string>("target", "");
    validate_camera_model(m, path.string());
    return m;
}

void write_camera_model(const std::filesystem::path& path, const CameraModel& m) {
    validate_camera_model(m, path.string());
    cv::FileStorage fs(
        ".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
    fs.writeComment(
        " tirpol camera model (docs/camera-geometry.md). OpenCV conventions: pixel (0,0) is the "
        "centre\n"
        " of the top-left pixel, u right, v down; camera x right, y down, z forward; units "
        "pixels.");
    fs << "image_width" << m.width << "image_height" << m.height;
    fs << "camera_matrix"
       << (cv::Mat_<double>(3, 3) << m.fx, 0.0, m.cx, 0.0, m.fy, m.cy, 0.0, 0.0, 1.0);
    fs << "distortion_model" << m.distortion_model();
    fs << "distortion_coefficients" << cv::Mat(m.distortion, true).reshape(1, 1);
    if (m.views > 0) {
        fs << "rms_reprojection_error_px" << m.rms_px << "views" << m.views;
        if (!m.std_dev.empty())
            fs << "std_dev_intrinsics" << cv::Mat(m.std_dev, true).reshape(1, 1);
    }
    if (!m.target.empty()) fs << "target" << m.target;
    commit_storage(fs, path);
}

CameraPose read_camera_pose(const std::filesystem::path& path) {
    const ConfigNode fs = parse_opencv_yaml(path);
    CameraPose p;
    const std::vector<double> r = required_matrix(fs, "rotation_camera_from_world", 3, 3);
    const std::vector<double> t = required_matrix(fs, "translation_m", 3, 1);
    for (int i = 0; i < 3; ++i) {
        p.translation_m[i] = t[static_cast<std::size_t>(i)];
        for (int j = 0; j < 3; ++j)
            p.camera_from_world(i, j) = r[static_cast<std::size_t>(3 * i + j)];
    }
    if ((p.camera_from_world * p.camera_from_world.transpose() - Mat3::Identity()).norm() > 1e-6 ||
        p.camera_from_world.determinant() < 0.0)
        fail("{}: rotation_camera_from_world is not a proper rotation (R·Rᵀ = I, det R = +1)",
             path.string());
    if (!p.translation_m.allFinite()) fail("{}: translation_m is not finite", path.string());
    p.rms_px = optional_real(fs, "rms_reprojection_error_px");
    p.points = fs.get_or<int>("control_points", 0);
    return p;
}

void write_camera_pose(const std::filesystem::path& path, const CameraPose& p) {
    cv::FileStorage fs(
        ".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
    fs.writeComment(
        " tirpol camera pose (docs/camera-geometry.md): x_camera = R x_world + t, world frame of "
        "the\n"
        " scene (x east, y north, z up), camera x right, y down, z forward; metres.");
    cv::Mat r(3, 3, CV_64F), t(3, 1, CV_64F), c(3, 1, CV_64F);
    const Vec3 position = p.position_m();
    for (int i = 0; i < 3; ++i) {
        t.at<double>(i) = p.translation_m[i];
        c.at<double>(i) = position[i];
        for (int j = 0; j < 3; ++j) r.at<double>(i, j) = p.camera_from_world(i, j);
    }
    fs << "rotation_camera_from_world" << r << "translation_m" << t << "camera_position_m" << c;
    if (p.points > 0) {
        fs << "control_points" << p.points << "rms_reprojection_error_px" << p.rms_px;
        fs << "rotation_sigma_deg"
           << cv::Mat(cv::Vec3d(p.rotation_sigma_deg.x(), p.rotation_sigma_deg.y(),
                                p.rotation_sigma_deg.z()));
        fs << "position_sigma_m"
           << cv::Mat(cv::Vec3d(p.position_sigma_m.x(), p.position_sigma_m.y(),
                                p.position_sigma_m.z()));
    }
    commit_storage(fs, path);
}

}  // namespace tirpol
