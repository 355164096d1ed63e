// `tirpol calibrate geometric|pose`: lens intrinsics and distortion from views of a target, and the
// camera's pose from surveyed control points (docs/camera-geometry.md). Parsing and printing only.

#include <cstdio>
#include <memory>

#include "cli.h"
#include "tirpol/calibration/geometric_calibration.h"
#include "tirpol/calibration/pose_estimation.h"
#include "tirpol/core/camera_model.h"

namespace tirpol::cli {

namespace {
struct GeometricArgs {
    std::vector<std::string> frames;
    std::string target, output, distortion_model = "standard";
    bool fix_k3 = false, zero_tangential = false, force = false;
    int min_views = 5;
};

void run_geometric(const GeometricArgs& a) {
    OutputGuard guard;
    for (const std::string& frame : a.frames) guard.input(frame, "FRAMES");
    guard.output_file(a.output, "--output").check(a.force);
    calibration::GeometricCalibrationOptions options;
    options.distortion_model = a.distortion_model;
    options.fix_k3 = a.fix_k3;
    options.zero_tangential = a.zero_tangential;
    options.min_views = a.min_views;
    const auto target = parse_option_value(
        "--target", [&] { return calibration::CalibrationTarget::parse(a.target); });
    const std::vector<std::filesystem::path> frames(a.frames.begin(), a.frames.end());
    const auto r = calibration::calibrate_geometric_frames(frames, target, options);
    write_camera_model(a.output, r.model);
    const auto& m = r.model;
    std::printf("geometric calibration: %zu of %zu frames show %s; %d×%d, %s distortion model\n",
                r.views.size(), frames.size(), target.to_string().c_str(), m.width, m.height,
                m.distortion_model().c_str());
    for (std::size_t i = 0; i < r.frames_without_target.size(); ++i)
        std::printf("  target not found: %s (%s)\n", r.frames_without_target[i].c_str(),
                    r.why_target_not_found[i].c_str());
    std::printf("  %-40s %9s %8s\n", "view", "RMS px", "tilt °");
    for (const auto& v : r.views)
        std::printf("  %-40s %9.4f %8.1f%s\n", v.name.c_str(), v.rms_px, v.tilt_deg,
                    v.outlier ? "  OUTLIER (check detection)" : "");
    std::printf("  total RMS reprojection error %.4f px\n", m.rms_px);
    std::vector<double> values = {m.fx, m.fy, m.cx, m.cy};
    values.insert(values.end(), m.distortion.begin(), m.distortion.end());
    for (std::size_t i = 0; i < values.size(); ++i)
        std::printf("  %-3s = %12.6g ± %.3g (1σ)\n", r.parameter_names[i].c_str(), values[i],
                    m.std_dev[i]);
    std::printf("  written: %s\n", a.output.c_str());
}

struct PoseArgs {
    std::string camera, points, output;
    double ransac_threshold_px = 3.0;
    bool force = false;
};

void run_pose(const PoseArgs& a) {
    OutputGuard()
        .input(a.camera, "--camera")
        .input(a.points, "--points")
        .output_file(a.output, "--output")
        .check(a.force);
    const CameraModel model = read_camera_model(a.camera);
    const auto points = calibration::read_control_points(a.points);
    calibration::PoseOptions options;
    options.ransac_threshold_px = a.ransac_threshold_px;
    const auto r = calibration::estimate_pose(model, points, options);
    write_camera_pose(a.output, r.pose);
    const auto& p = r.pose;
    const Vec3 c = p.position_m();
    std::printf("camera pose from %d of %zu control points, RMS reprojection error %.3f px\n",
                p.points, points.size(), p.rms_px);
    std::printf("  position (world) %.4f %.4f %.4f m ± %.4f %.4f %.4f (1σ)\n", c.x(), c.y(), c.z(),
                p.position_sigma_m.x(), p.position_sigma_m.y(), p.position_sigma_m.z());
    std::printf("  rotation 1σ about camera x y z: %.4f %.4f %.4f °\n", p.rotation_sigma_deg.x(),
                p.rotation_sigma_deg.y(), p.rotation_sigma_deg.z());
    for (std::size_t i = 0; i < points.size(); ++i)
        std::printf("  %-16s residual %8.3f px%s\n", points[i].name.c_str(), r.residual_px[i],
                    r.inlier[i] ? "" : "  OUTLIER (not used)");
    std::printf("  written: %s\n", a.output.c_str());
}

void register_calibrate_geometry(CLI::App& app) {
    auto* cmd = app.get_subcommand("calibrate");  // added by calibrate.cpp (order 50)

    auto g = std::make_shared<GeometricArgs>();
    auto* geo = cmd->add_subcommand(
        "geometric", "Lens intrinsics and distortion from views of a checkerboard or circle grid");
    geo->add_option("FRAMES", g->frames, "Frames showing the target (EXR counts/S0, PNG, TIFF)")
        ->required()
        ->check(CLI::ExistingFile);
    geo->add_option("--target", g->target,
                    "checkerboard:COLSxROWS:SQUARE_M (inner corners) | circles:COLSxROWS:PITCH_M | "
                    "acircles:COLSxROWS:HALF_PITCH_M")
        ->required();
    geo->add_option("-o,--output", g->output, "Camera model YAML to write (OpenCV FileStorage)")
        ->required();
    geo->add_option("--distortion-model", g->distortion_model,
                    "standard (k1 k2 p1 p2 k3) | rational | thin_prism")
        ->check(CLI::IsMember({"standard", "rational", "thin_prism"}))
        ->capture_default_str();
    geo->add_flag("--fix-k3", g->fix_k3, "Keep k3 = 0 (few views or a narrow lens)");
    geo->add_flag("--zero-tangential", g->zero_tangential, "Keep p1 = p2 = 0");
    geo->add_option("--min-views", g->min_views, "Fewer frames with the target is an error")
        ->capture_default_str();
    add_force_flag(geo, g->force);
    geo->callback([g] { run_geometric(*g); });

    auto p = std::make_shared<PoseArgs>();
    auto* pose = cmd->add_subcommand(
        "pose", "Camera pose in the scene's world frame from ≥ 4 surveyed control points");
    pose->add_option("--camera", p->camera, "Camera model YAML (from `calibrate geometric`)")
        ->required()
        ->check(CLI::ExistingFile);
    pose->add_option("--points", p->points,
                     "Control points CSV: name,x_m,y_m,z_m,u_px,v_px (OpenCV pixels)")
        ->required()
        ->check(CLI::ExistingFile);
    pose->add_option("-o,--output", p->output, "Camera pose YAML to write")->required();
    pose->add_option("--ransac-threshold-px", p->ransac_threshold_px, "Outlier threshold")
        ->capture_default_str();
    add_force_flag(pose, p->force);
    pose->callback([p] { run_pose(*p); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(51, register_calibrate_geometry);

}  // namespace tirpol::cli
