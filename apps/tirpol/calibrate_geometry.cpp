// `tirpol calibrate geometric|pose`: lens intrinsics and distortion from views of a target, and the
// camera's pose from surveyed control points (docs/camera-geometry.md). Parsing and printing only.

#include <memory>

#include "cli.h"
#include "common_options.h"
#include "tirpol/calibration/geometric_calibration.h"

namespace tirpol::cli {

namespace {
void run_geometric(const calibration::GeometricRunOptions& o) {
    const calibration::GeometricRun r = calibration::run_geometric_calibration(o);
    print_text(calibration::geometric_calibration_text(r.result, r.target, r.frames, r.output));
}

void run_pose(const calibration::PoseRunOptions& o) {
    const calibration::PoseRun r = calibration::run_pose_estimation(o);
    print_text(calibration::pose_estimation_text(r.result, r.points, r.output));
}

void register_calibrate_geometry(CLI::App& app) {
    auto* cmd = app.get_subcommand("calibrate");  // added by calibrate.cpp (order 50)

    auto g = std::make_shared<calibration::GeometricRunOptions>();
    auto* geo = cmd->add_subcommand(
        "geometric", "Lens intrinsics and distortion from views of a checkerboard or circle grid");
    add_required_input(geo, "FRAMES", g->frames,
                       "Frames showing the target (EXR counts/S0, PNG, TIFF)");
    geo->add_option("--target", g->target,
                    "checkerboard:COLSxROWS:SQUARE_M (inner corners) | circles:COLSxROWS:PITCH_M | "
                    "acircles:COLSxROWS:HALF_PITCH_M")
        ->required();
    add_output_option(geo, g->output, "Camera model YAML to write (OpenCV FileStorage)");
    geo->add_option("--distortion-model", g->calibration.distortion_model,
                    "standard (k1 k2 p1 p2 k3) | rational | thin_prism")
        ->check(CLI::IsMember({"standard", "rational", "thin_prism"}))
        ->capture_default_str();
    geo->add_flag("--fix-k3", g->calibration.fix_k3, "Keep k3 = 0 (few views or a narrow lens)");
    geo->add_flag("--zero-tangential", g->calibration.zero_tangential, "Keep p1 = p2 = 0");
    geo->add_option("--min-views", g->calibration.min_views,
                    "Fewer frames with the target is an error")
        ->capture_default_str();
    add_force_flag(geo, g->force);
    geo->callback([g] { run_geometric(*g); });

    auto p = std::make_shared<calibration::PoseRunOptions>();
    auto* pose = cmd->add_subcommand(
        "pose", "Camera pose in the scene's world frame from ≥ 4 surveyed control points");
    add_required_input(pose, "--camera", p->camera,
                       "Camera model YAML (from `calibrate geometric`)");
    add_required_input(pose, "--points", p->points,
                       "Control points CSV: name,x_m,y_m,z_m,u_px,v_px (OpenCV pixels)");
    add_output_option(pose, p->output, "Camera pose YAML to write");
    pose->add_option("--ransac-threshold-px", p->pose.ransac_threshold_px, "Outlier threshold")
        ->capture_default_str();
    add_force_flag(pose, p->force);
    pose->callback([p] { run_pose(*p); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(51, register_calibrate_geometry);

}  // namespace tirpol::cli
