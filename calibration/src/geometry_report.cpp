#include <fmt/printf.h>

#include "tirpol/calibration/geometric_calibration.h"

namespace tirpol::calibration {

std::string geometric_calibration_text(const GeometricCalibrationResult& r,
                                       const CalibrationTarget& target, std::size_t frames,
                                       const std::string& output) {
    const auto& m = r.model;
    std::string text = fmt::sprintf(
        "geometric calibration: %zu of %zu frames show %s; %d×%d, %s distortion model\n",
        r.views.size(), frames, target.to_string(), m.width, m.height, m.distortion_model());
    for (std::size_t i = 0; i < r.frames_without_target.size(); ++i)
        text += "  target not found: " + r.frames_without_target[i] + " (" +
                r.why_target_not_found[i] + ")\n";
    // The column heads as printf pads them (by bytes: "°" takes one column less).
    text += "  view                                        RMS px  tilt °\n";
    for (const auto& v : r.views)
        text += fmt::sprintf("  %-40s %9.4f %8.1f%s\n", v.name, v.rms_px, v.tilt_deg,
                             v.outlier ? "  OUTLIER (check detection)" : "");
    text += fmt::sprintf("  total RMS reprojection error %.4f px\n", m.rms_px);
    std::vector<double> values = {m.fx, m.fy, m.cx, m.cy};
    values.insert(values.end(), m.distortion.begin(), m.distortion.end());
    for (std::size_t i = 0; i < values.size(); ++i)
        text += fmt::sprintf("  %-3s = %12.6g ± %.3g (1σ)\n", r.parameter_names[i], values[i],
                             m.std_dev[i]);
    return text + "  written: " + output + "\n";
}

std::string pose_estimation_text(const PoseResult& r, const std::vector<ControlPoint>& points,
                                 const std::string& output) {
    const auto& p = r.pose;
    const Vec3 c = p.position_m();
    std::string text =
        fmt::sprintf("camera pose from %d of %zu control points, RMS reprojection error %.3f px\n",
                     p.points, points.size(), p.rms_px);
    text +=
        fmt::sprintf("  position (world) %.4f %.4f %.4f m ± %.4f %.4f %.4f (1σ)\n", c.x(), c.y(),
                     c.z(), p.position_sigma_m.x(), p.position_sigma_m.y(), p.position_sigma_m.z());
    text +=
        fmt::sprintf("  rotation 1σ about camera x y z: %.4f %.4f %.4f °\n",
                     p.rotation_sigma_deg.x(), p.rotation_sigma_deg.y(), p.rotation_sigma_deg.z());
    for (std::size_t i = 0; i < points.size(); ++i)
        text += fmt::sprintf("  %-16s residual %8.3f px%s\n", points[i].name, r.residual_px[i],
                             r.inlier[i] ? "" : "  OUTLIER (not used)");
    return text + "  written: " + output + "\n";
}

}  // namespace tirpol::calibration
