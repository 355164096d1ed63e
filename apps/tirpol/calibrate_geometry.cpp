// `tirpol calibrate geometric|pose`: lens intrinsics and distortion from views of a target, and the
// camera's pose from surveyed control points (docs/camera-geometry.md). Parsing and printing only.

#include <memory>

#include "cli.h"
#include "common_options.h"
#include "tirpol/calibration/geometric_calibration.h"
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
    print_text(calibration::geometric_calibration_text(r, target, frames.size(), a.output));
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
    print_text(calibration::pose_estimation_text(r, points, a.output));
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
    add_output_option(geo, g->output, "Camera model YAML to write (OpenCV FileStorage)");
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
    add_output_option(pose, p->output, "Camera pose YAML to write");
    pose->add_option("--ransac-threshold-px", p->ransac_threshold_px, "Outlier threshold")
        ->capture_default_str();
    add_force_flag(pose, p->force);
    pose->callback([p] { run_pose(*p); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(51, register_calibrate_geometry);

}  // namespace tirpol::cli
