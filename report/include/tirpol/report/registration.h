#pragma once
/// \file registration.h
/// Registration of a simulated Stokes image onto the measured image's pixel grid. The geometric
/// model is a plane homography H (Hartley & Zisserman, "Multiple View Geometry", 2nd ed., §4.1)
/// mapping a measured pixel to the simulated pixel that sees the same scene point:
/// (x_s, y_s, 1)ᵀ ∝ H (x_m, y_m, 1)ᵀ. It comes from control points (least squares over ≥ 4 pairs,
/// cv::findHomography), or automatically from the enhanced-correlation-coefficient maximisation of
/// Evangelidis & Psarakis (IEEE TPAMI 30(10), 2008; cv::findTransformECC) on the gradient magnitude
/// of S0, which is insensitive to the gain/offset differences between a measurement and a render.
///
/// A simulation rendered through the measured camera's calibrated model (intrinsics, distortion and
/// pose from `tirpol calibrate geometric|pose`) already lies on the measured pixel grid:
/// registration by camera model checks that it was (the renderer's header attributes against the
/// model) and warps nothing — a homography cannot undo lens distortion or parallax, the camera
/// model does.
///
/// The residual misalignment after registration is measured independently of the method by phase
/// correlation (Kuglin & Hines 1975; cv::phaseCorrelate) between the measured and the registered
/// simulated S0 gradient magnitude.
///
/// Limitation: a homography with a rotation also rotates the polarization reference frame by the
/// same angle; S1/S2 are not rotated back (the rotation is reported; it is ≈ 0 for a simulated
/// camera that matches the real one).

#include <array>
#include <atomic>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tirpol/core/camera_model.h"
#include "tirpol/core/image.h"
#include "tirpol/report/regions.h"

namespace tirpol::report {

enum class RegistrationMethod {
    None,  ///< identity; images must have the same size
    Auto,  ///< ECC on S0 gradient magnitude (homography, falling back to affine, translation)
    ControlPoints,  ///< homography from control points
    CameraModel,    ///< identity: the simulation was rendered through the measured camera's
                    ///< calibrated model
};

/// "none" | "auto" | "control-points" | "camera-model"; throws tirpol::Error naming the accepted
/// values otherwise.
RegistrationMethod parse_registration_method(std::string_view text);
std::string to_string(RegistrationMethod method);

/// One tie point: the same scene feature in the measured and the simulated image (pixel
/// coordinates).
struct TiePoint {
    PixelPoint measured;
    PixelPoint simulated;
};

/// Reads control points from YAML: a list of `{measured: [x, y], simulated: [x, y]}` mappings.
/// Throws tirpol::Error naming file:line:field for a malformed entry or an unknown key.
std::vector<TiePoint> load_control_points(const std::filesystem::path& path);

/// Relative reduction of the S0 edge mismatch an automatic warp must bring to replace the identity.
inline constexpr double kRegistrationMinImprovement = 0.10;

struct Registration {
    RegistrationMethod method = RegistrationMethod::None;
    /// Model actually used: "identity", "homography", "affine" or "translation".
    std::string model = "identity";
    /// Row-major 3×3 H: simulated pixel ∝ H · measured pixel (homogeneous).
    std::array<double, 9> measured_to_simulated{1, 0, 0, 0, 1, 0, 0, 0, 1};
    /// RMS distance in simulated pixels between H(measured) and simulated over the control points.
    std::optional<double> control_point_rms_px;
    /// Final ECC correlation coefficient (automatic registration only), in [-1, 1].
    std::optional<double> ecc_correlation;
    /// Residual misalignment after registration (phase correlation of S0 gradients), pixels.
    std::array<double, 2> residual_shift_px{0.0, 0.0};
    /// Largest displacement H applies at the four image corners, pixels (0 for identity).
    double max_corner_displacement_px = 0.0;
    /// Rotation of the image axes implied by H at the image centre, degrees (counter-clockwise).
    double rotation_deg = 0.0;
    /// Automatic registration of equal-size images: mean squared difference of the S0 edge strength
    /// (gradient magnitude at σ = 2 px) without and with the warp; the warp is kept only when it
    /// lowers the mismatch by more than kRegistrationMinImprovement.
    std::optional<double> identity_edge_mismatch, registered_edge_mismatch;
    /// What happened, for the report ("images already match", "ECC homography did not converge;
    /// used affine").
    std::string note;
};

/// Registers `simulated` onto `measured` (both with an S0 channel). With Auto, images of equal size
/// keep the identity unless the ECC warp lowers the S0 edge mismatch by more than
/// kRegistrationMinImprovement (an aligned pair is never warped); images of different
/// sizes are first resized when their aspect ratios agree within 1 %; otherwise, and for None with
/// different sizes, throws tirpol::Error asking for control points. ControlPoints needs ≥ 4 pairs.
/// `cancel` (null: never) is read before each ECC pyramid level; once set, tirpol::Cancelled is
/// thrown.
Registration register_images(const Image& measured, const Image& simulated,
                             RegistrationMethod method, const std::vector<TiePoint>& control_points,
                             const std::atomic<bool>* cancel = nullptr);

/// Registration by camera model: checks that `simulated` was rendered through `camera` (same size
/// as it and as `measured`; the renderer's `camera_intrinsics_px` = fx fy cx cy, OpenCV pixel
/// convention, and `camera_distortion` header attributes equal the model's to float precision) and
/// returns the identity with the residual misalignment measured by phase correlation. Throws
/// tirpol::Error naming `camera_name` and the field that disagrees, or the missing attribute.
Registration register_by_camera_model(const Image& measured, const Image& simulated,
                                      const CameraModel& camera, const std::string& camera_name);

/// Resamples every channel of `simulated` onto the measured grid (width × height) through the
/// registration (bilinear; nearest for integer label channels object_id/material_id). Pixels that
/// map outside the simulated image are NaN. Channels named *_var (*_std) are scaled by Σ w_k² (its
/// square root), the variance of a bilinear interpolation of independent samples, so that they stay
/// the variance of the resampled Monte-Carlo mean. Identity registration of an equal-size image
/// copies it.
Image resample_to_measured(const Image& simulated, const Registration& registration, int width,
                           int height);

}  // namespace tirpol::report
