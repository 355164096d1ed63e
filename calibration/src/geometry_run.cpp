#include "tirpol/calibration/geometric_calibration.h"
#include "tirpol/core/camera_model.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"

namespace tirpol::calibration {

GeometricRun run_geometric_calibration(const GeometricRunOptions& o) {
    OutputGuard guard;
    for (const std::string& frame : o.frames) guard.input(frame, "FRAMES");
    guard.output_file(o.output, "--output").check(o.force);
    GeometricRun run;
    try {
        run.target = CalibrationTarget::parse(o.target);
    } catch (const Error& e) {
        throw OptionValueError("--target", e.what());
    }
    const std::vector<std::filesystem::path> frames(o.frames.begin(), o.frames.end());
    run.result = calibrate_geometric_frames(frames, run.target, o.calibration);
    run.frames = frames.size();
    run.output = o.output;
    write_camera_model(o.output, run.result.model);
    return run;
}

PoseRun run_pose_estimation(const PoseRunOptions& o) {
    OutputGuard()
        .input(o.camera, "--camera")
        .input(o.points, "--points")
        .output_file(o.output, "--output")
        .check(o.force);
    const CameraModel model = read_camera_model(o.camera);
    PoseRun run;
    run.points = read_control_points(o.points);
    run.result = estimate_pose(model, run.points, o.pose);
    run.output = o.output;
    write_camera_pose(o.output, run.result.pose);
    return run;
}

}  // namespace tirpol::calibration
