#include "tirpol/simulation/pinhole_camera.h"

#include <cmath>
#include <filesystem>

#include "tirpol/core/error.h"

namespace tirpol::simulation {

namespace {
Vec3 vec3_field(const ConfigNode& node, std::string_view key) {
    const ConfigNode child = node.at(key);
    const auto v = child.as<std::vector<double>>();
    if (v.size() != 3) child.fail(fmt::format("expected 3 numbers [x, y, z], got {}", v.size()));
    return {v[0], v[1], v[2]};
}
}  // namespace

PinholeCamera::PinholeCamera(int width, int height, CameraIntrinsics intrinsics, Vec3 position,
                             Mat3 world_from_camera)
    : m_width(width),
      m_height(height),
      m_intrinsics(intrinsics),
      m_position(std::move(position)),
      m_world_from_camera(std::move(world_from_camera)) {
    if (width <= 0 || height <= 0)
        fail("camera: resolution must be positive, got {}x{}", width, height);
    if (!(intrinsics.fx > 0.0 && intrinsics.fy > 0.0))
        fail("camera: focal lengths fx, fy must be positive, got {} {}", intrinsics.fx,
             intrinsics.fy);
    const auto& k = intrinsics;
    m_lens.width = width;
    m_lens.height = height;
    m_lens.fx = k.fx;
    m_lens.fy = k.fy;
    m_lens.cx = k.cx - 0.5;
    m_lens.cy = k.cy - 0.5;
    m_lens.distortion = {k.k1, k.k2, k.p1, k.p2, k.k3, k.k4, k.k5, k.k6, k.s1, k.s2, k.s3, k.s4};
    // Keep the shortest OpenCV layout that holds every non-zero coefficient (5, 8 or 12).
    if (k.s1 == 0.0 && k.s2 == 0.0 && k.s3 == 0.0 && k.s4 == 0.0) m_lens.distortion.resize(8);
    if (m_lens.distortion.size() == 8 && k.k4 == 0.0 && k.k5 == 0.0 && k.k6 == 0.0)
        m_lens.distortion.resize(5);
}

PinholeCamera PinholeCamera::from_model(const CameraModel& model, const CameraPose& pose) {
    validate_camera_model(model, "camera model");
    CameraIntrinsics k;
    k.fx = model.fx;
    k.fy = model.fy;
    k.cx = model.cx + 0.5;  // OpenCV's pixel-centre origin → this class's corner origin
    k.cy = model.cy + 0.5;
    double* coefficients[] = {&k.k1, &k.k2, &k.p1, &k.p2, &k.k3, &k.k4,
                              &k.k5, &k.k6, &k.s1, &k.s2, &k.s3, &k.s4};
    for (std::size_t i = 0; i < model.distortion.size(); ++i)
        *coefficients[i] = model.distortion[i];
    return PinholeCamera(model.width, model.height, k, pose.position_m(),
                         pose.camera_from_world.transpose());
}

CameraPose PinholeCamera::pose() const {
    CameraPose p;
    p.camera_from_world = m_world_from_camera.transpose();
    p.translation_m = -p.camera_from_world * m_position;
    return p;
}

std::optional<Eigen::Vector2d> PinholeCamera::project(const Vec3& world_point) const {
    const Vec3 c = m_world_from_camera.transpose() * (world_point - m_position);
    if (!(c.z() > 0.0)) return std::nullopt;
    return m_lens.project(c) + Eigen::Vector2d(0.5, 0.5);
}

Mat3 PinholeCamera::look_at(const Vec3& position, const Vec3& target, const Vec3& up) {
    const Vec3 forward = (target - position).normalized();
    Vec3 right = forward.cross(up);
    if (right.norm() < 1e-9)
        fail("camera: look_at direction is parallel to up; give another up vector");
    right.normalize();
    const Vec3 down = forward.cross(right);  // OpenCV: x right, y down, z forward, x × y = z
    Mat3 m;
    m.col(0) = right;
    m.col(1) = down;
    m.col(2) = forward;
    return m;
}

namespace {
/// `model: FILE.yaml` — a calibrated camera model; excludes the hand-written lens keys.
CameraModel model_of(const ConfigNode& node) {
    for (const char* key : {"fov_deg", "intrinsics", "distortion"})
        if (node.has(key))
            node.at(key).fail("'model' gives the intrinsics and distortion; remove this key");
    const ConfigNode m = node.at("model");
    const auto path = m.resolve_path(m.as<std::string>());
    if (!std::filesystem::is_regular_file(path))
        m.fail("camera model file not found: " + path.string());
    CameraModel model;
    try {
        model = read_camera_model(path);
    } catch (const Error& e) {
        m.fail(e.what());
    }
    if (auto r = node.find("resolution")) {
        const auto res = r->as<std::vector<double>>();
        if (res.size() != 2 || res[0] != model.width || res[1] != model.height)
            r->fail(
                fmt::format("the camera model {} is {}x{}; resolution must match it or be left out",
                            path.string(), model.width, model.height));
    }
    return model;
}

CameraIntrinsics hand_written_intrinsics(const ConfigNode& node, int w, int h) {
    CameraIntrinsics k;
    const bool has_fov = node.has("fov_deg"), has_k = node.has("intrinsics");
    if (has_fov == has_k)
        node.fail(
            "give exactly one of fov_deg (horizontal field of view), intrinsics {fx, fy, cx, cy} "
            "or model: FILE.yaml");
    if (has_fov) {
        const double fov = deg_to_rad(node.get_in_range("fov_deg", 0.1, 179.0));
        k.fx = k.fy = 0.5 * w / std::tan(0.5 * fov);
        k.cx = 0.5 * w;
        k.cy = 0.5 * h;
    } else {
        const ConfigNode in = node.at("intrinsics");
        in.check_keys({"fx", "fy", "cx", "cy"});
        k.fx = in.get_in_range("fx", 1e-6, 1e9);
        k.fy = in.get_in_range("fy", 1e-6, 1e9);
        k.cx = in.get<double>("cx");
        k.cy = in.get<double>("cy");
    }
    if (auto d = node.find("distortion")) {
        d->check_keys({"k1", "k2", "p1", "p2", "k3"});
        k.k1 = d->get_or("k1", 0.0);
        k.k2 = d->get_or("k2", 0.0);
        k.p1 = d->get_or("p1", 0.0);
        k.p2 = d->get_or("p2", 0.0);
        k.k3 = d->get_or("k3", 0.0);
    }
    return k;
}

/// The pose: `pose: FILE.yaml` (from `tirpol calibrate pose`), or position + look_at/rotation.
CameraPose pose_of(const ConfigNode& node) {
    if (auto f = node.find("pose")) {
        for (const char* key : {"position", "look_at", "up", "rotation"})
            if (node.has(key))
                node.at(key).fail(
                    "'pose' gives the camera position and orientation; remove this key");
        const auto path = f->resolve_path(f->as<std::string>());
        if (!std::filesystem::is_regular_file(path))
            f->fail("camera pose file not found: " + path.string());
        try {
            return read_camera_pose(path);
        } catch (const Error& e) {
            f->fail(e.what());
        }
    }
    const Vec3 position = vec3_field(node, "position");
    Mat3 world_from_camera;
    if (node.has("look_at") == node.has("rotation"))
        node.fail(
            "give exactly one of look_at [x, y, z], rotation (9 numbers, OpenCV R "
            "camera-from-world, row-major) or pose: FILE.yaml");
    if (node.has("look_at")) {
        const Vec3 up = node.has("up") ? vec3_field(node, "up") : world_up();
        const Vec3 target = vec3_field(node, "look_at");
        if ((target - position).norm() < 1e-12)
            node.at("look_at").fail("look_at equals the camera position");
        world_from_camera = PinholeCamera::look_at(position, target, up);
    } else {
        if (node.has("up")) node.at("up").fail("'up' only goes with look_at");
        const ConfigNode r_node = node.at("rotation");
        const auto r = r_node.as<std::vector<double>>();
        if (r.size() != 9) r_node.fail("expected 9 numbers (3×3 rotation, row-major)");
        Mat3 camera_from_world;
        camera_from_world << r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8];
        if ((camera_from_world * camera_from_world.transpose() - Mat3::Identity()).norm() > 1e-6 ||
            camera_from_world.determinant() < 0.0)
            r_node.fail("not a proper rotation matrix (R·Rᵀ = I, det R = +1)");
        world_from_camera = camera_from_world.transpose();
    }
    CameraPose pose;
    pose.camera_from_world = world_from_camera.transpose();
    pose.translation_m = -pose.camera_from_world * position;
    return pose;
}
}  // namespace

PinholeCamera PinholeCamera::from_config(const ConfigNode& node) {
    node.check_keys({"resolution", "fov_deg", "intrinsics", "distortion", "model", "position",
                     "look_at", "up", "rotation", "pose"});
    const CameraPose pose = pose_of(node);
    if (node.has("model")) return from_model(model_of(node), pose);

    const ConfigNode res_node = node.at("resolution");
    const auto res = res_node.as<std::vector<double>>();
    if (res.size() != 2 || res[0] < 1 || res[1] < 1 || res[0] != std::floor(res[0]) ||
        res[1] != std::floor(res[1]))
        res_node.fail("expected [width, height] in pixels (positive integers)");
    const int w = static_cast<int>(res[0]), h = static_cast<int>(res[1]);
    return PinholeCamera(w, h, hand_written_intrinsics(node, w, h), pose.position_m(),
                         pose.camera_from_world.transpose());
}

PinholeCamera PinholeCamera::resized(int width, int height) const {
    CameraIntrinsics k = m_intrinsics;
    const double sx = static_cast<double>(width) / m_width,
                 sy = static_cast<double>(height) / m_height;
    k.fx *= sx;
    k.cx *= sx;
    k.fy *= sy;
    k.cy *= sy;
    return PinholeCamera(width, height, k, m_position, m_world_from_camera);
}

PinholeCamera PinholeCamera::rotated(const Mat3& rotation) const {
    return PinholeCamera(m_width, m_height, m_intrinsics, rotation * m_position,
                         rotation * m_world_from_camera);
}

Vec3 PinholeCamera::ray_direction(double u, double v) const {
    const Vec2 p = m_lens.undistort(Vec2(u - 0.5, v - 0.5));
    return (m_world_from_camera * Vec3(p.x(), p.y(), 1.0)).normalized();
}

StokesFrame PinholeCamera::image_frame(const Vec3& direction) const {
    return frame_from_reference(-direction, m_world_from_camera.col(0));
}

}  // namespace tirpol::simulation
