#include "tirpol/report/registration.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include "tirpol/core/config.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/interrupt_signals.h"

namespace tirpol::report {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

cv::Mat plane(const Image& image, const std::string& name) {
    const auto& data = image.channel(name);
    return cv::Mat(image.height(), image.width(), CV_32F, const_cast<float*>(data.data())).clone();
}

cv::Mat finite_mask(const cv::Mat& m) {
    cv::Mat mask(m.size(), CV_8U);
    for (int y = 0; y < m.rows; ++y)
        for (int x = 0; x < m.cols; ++x)
            mask.at<uchar>(y, x) = std::isfinite(m.at<float>(y, x)) ? 255 : 0;
    return mask;
}

// Replaces non-finite pixels by the mean of the finite ones, so filters do not spread NaN.
cv::Mat fill_non_finite(const cv::Mat& m, const cv::Mat& mask) {
    cv::Mat out = m.clone();
    const double fill = cv::countNonZero(mask) > 0 ? cv::mean(m, mask)[0] : 0.0;
    out.setTo(fill, ~mask);
    return out;
}

// Gradient magnitude of the smoothed image: edges are where a measurement and a render agree in
// position even when their levels (calibration offsets, emissivity errors) do not.
cv::Mat gradient_magnitude(const cv::Mat& s0) {
    const cv::Mat mask = finite_mask(s0);
    cv::Mat smooth, gx, gy, mag;
    cv::GaussianBlur(fill_non_finite(s0, mask), smooth, {0, 0}, 1.0);
    cv::Sobel(smooth, gx, CV_32F, 1, 0, 3);
    cv::Sobel(smooth, gy, CV_32F, 0, 1, 3);
    cv::magnitude(gx, gy, mag);
    return mag;
}

cv::Matx33d to_matx(const std::array<double, 9>& h) {
    return {h[0], h[1], h[2], h[3], h[4], h[5], h[6], h[7], h[8]};
}
std::array<double, 9> to_array(const cv::Matx33d& m) {
    cv::Matx33d n = m * (1.0 / m(2, 2));
    return {n(0, 0), n(0, 1), n(0, 2), n(1, 0), n(1, 1), n(1, 2), n(2, 0), n(2, 1), n(2, 2)};
}
cv::Point2d apply(const cv::Matx33d& h, cv::Point2d p) {
    const cv::Vec3d q = h * cv::Vec3d(p.x, p.y, 1.0);
    return {q[0] / q[2], q[1] / q[2]};
}

double max_corner_displacement(const cv::Matx33d& h, int width, int height) {
    double worst = 0.0;
    for (const cv::Point2d c : {cv::Point2d(0, 0), cv::Point2d(width - 1, 0),
                                cv::Point2d(0, height - 1), cv::Point2d(width - 1, height - 1)})
        worst = std::max(worst, cv::norm(apply(h, c) - c));
    return worst;
}

double rotation_deg(const cv::Matx33d& h, int width, int height) {
    // Angle of the linear part of H at the image centre (finite differences of the mapping).
    const cv::Point2d c((width - 1) / 2.0, (height - 1) / 2.0);
    const cv::Point2d ex = apply(h, c + cv::Point2d(1, 0)) - apply(h, c);
    return std::atan2(ex.y, ex.x) * 180.0 / CV_PI;
}

// Homography between pyramid level `level` and full resolution: x_full = 2^level · x_level.
cv::Matx33d to_level(const cv::Matx33d& h, int level) {
    const double s = std::ldexp(1.0, level);
    const cv::Matx33d scale(s, 0, 0, 0, s, 0, 0, 0, 1);
    return scale.inv() * h * scale;
}
cv::Matx33d from_level(const cv::Matx33d& h, int level) {
    const double s = std::ldexp(1.0, level);
    const cv::Matx33d scale(s, 0, 0, 0, s, 0, 0, 0, 1);
    return scale * h * scale.inv();
}

cv::Mat to_warp(const cv::Matx33d& h, int motion) {
    if (motion == cv::MOTION_HOMOGRAPHY) {
        cv::Mat w;
        cv::Mat(h, true).convertTo(w, CV_32F);  // findTransformECC works on single-precision warps
        return w;
    }
    cv::Mat w(2, 3, CV_32F);
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 3; ++c) w.at<float>(r, c) = static_cast<float>(h(r, c));
    return w;
}
cv::Matx33d from_warp(const cv::Mat& w) {
    cv::Mat d;
    w.convertTo(d, CV_64F);
    cv::Matx33d h = cv::Matx33d::eye();
    for (int r = 0; r < d.rows; ++r)
        for (int c = 0; c < 3; ++c) h(r, c) = d.at<double>(r, c);
    return h;
}

const char* motion_name(int motion) {
    switch (motion) {
        case cv::MOTION_HOMOGRAPHY:
            return "homography";
        case cv::MOTION_AFFINE:
            return "affine";
        default:
            return "translation";
    }
}

struct EccOutcome {
    cv::Matx33d h;
    double correlation = 0.0;
    int motion = cv::MOTION_TRANSLATION;
    std::string note;
};

// Coarse-to-fine ECC of `input` against `templ` (same size), from a phase-correlation start.
// Tries a homography, then affine, then translation, keeping the first that converges to a
// plausible warp (corner displacement within a quarter of the image beyond the start).
EccOutcome ecc_register(const cv::Mat& templ, const cv::Mat& input, const cv::Mat& templ_mask,
                        const std::atomic<bool>* cancel) {
    cv::Mat window;
    cv::createHanningWindow(window, templ.size(), CV_32F);
    const cv::Point2d start = cv::phaseCorrelate(templ, input, window);
    const cv::Matx33d initial(1, 0, start.x, 0, 1, start.y, 0, 0, 1);

    int levels = 0;
    while (levels < 3 && std::min(templ.cols, templ.rows) >> (levels + 1) >= 48) ++levels;
    std::vector<cv::Mat> templs{templ}, inputs{input}, masks{templ_mask};
    for (int l = 1; l <= levels; ++l) {
        cv::Mat t, i, m;
        cv::pyrDown(templs.back(), t);
        cv::pyrDown(inputs.back(), i);
        cv::resize(masks.back(), m, t.size(), 0, 0, cv::INTER_NEAREST);
        templs.push_back(t);
        inputs.push_back(i);
        masks.push_back(m);
    }

    std::string failures;
    const double limit = 0.25 * std::min(templ.cols, templ.rows);
    for (int motion : {cv::MOTION_HOMOGRAPHY, cv::MOTION_AFFINE, cv::MOTION_TRANSLATION}) {
        try {
            cv::Matx33d h = initial;
            double rho = 0.0;
            for (int l = levels; l >= 0; --l) {
                throw_if_cancelled(cancel, "registration");
                cv::Mat w = to_warp(to_level(h, l), motion);
                // Coarse levels do the travelling; the full-resolution level only polishes.
                const cv::TermCriteria criteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS,
                                                l == 0 ? 25 : 100, 1e-6);
                rho = cv::findTransformECC(templs[static_cast<std::size_t>(l)],
                                           inputs[static_cast<std::size_t>(l)], w, motion, criteria,
                                           masks[static_cast<std::size_t>(l)], 5);
                h = from_level(from_warp(w), l);
            }
            const double moved = max_corner_displacement(initial.inv() * h, templ.cols, templ.rows);
            if (!std::isfinite(moved) || moved > limit) {
                failures += fmt::format("ECC {} diverged (corner moved {:.1f} px); ",
                                        motion_name(motion), moved);
                continue;
            }
            return {h, rho, motion,
                    failures.empty() ? std::string() : failures + "used " + motion_name(motion)};
        } catch (const cv::Exception& e) {
            failures += fmt::format("ECC {} did not converge; ", motion_name(motion));
        }
    }
    fail(
        "automatic registration failed ({}); give control points (--control-points CP.yaml with ≥ "
        "4 pairs "
        "measured (x, y) ↔ simulated (x, y))",
        failures);
}

// Residual misalignment: phase correlation between the measured S0 gradient and the registered
// simulated S0 gradient, both zeroed where the registered image has no data.
std::array<double, 2> residual_shift(const Image& measured, const Image& registered) {
    const cv::Mat m = plane(measured, "S0"), r = plane(registered, "S0");
    cv::Mat valid = finite_mask(r) & finite_mask(m);
    cv::erode(valid, valid, cv::getStructuringElement(cv::MORPH_RECT, {7, 7}));
    if (cv::countNonZero(valid) < 64) return {kNaN, kNaN};
    cv::Mat gm = gradient_magnitude(m), gr = gradient_magnitude(r);
    gm.setTo(0.0, ~valid);
    gr.setTo(0.0, ~valid);
    cv::Mat window;
    cv::createHanningWindow(window, gm.size(), CV_32F);
    const cv::Point2d d = cv::phaseCorrelate(gm, gr, window);
    return {d.x, d.y};
}

// Mismatch of the S0 edges after mapping the simulation through `h`: mean squared difference of the
// gradient magnitudes of both images blurred at σ = 2 px, over pixels at least 6 px from missing
// data. The blur makes the smoothing of a sub-pixel bilinear resampling negligible, so an aligned
// noisy pair does not look "better" warped just because interpolation averages its noise.
double edge_mismatch(const Image& measured, const Image& simulated, const cv::Matx33d& h,
                     const cv::Mat& valid) {
    const cv::Mat m = plane(measured, "S0");
    cv::Mat s = plane(simulated, "S0");
    if (h != cv::Matx33d::eye())
        cv::warpPerspective(s.clone(), s, h, m.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                            cv::BORDER_CONSTANT, cv::Scalar(kNaN));
    auto edges = [](const cv::Mat& img) {
        cv::Mat smooth, gx, gy, mag;
        cv::GaussianBlur(fill_non_finite(img, finite_mask(img)), smooth, {0, 0}, 2.0);
        cv::Sobel(smooth, gx, CV_32F, 1, 0, 3);
        cv::Sobel(smooth, gy, CV_32F, 0, 1, 3);
        cv::magnitude(gx, gy, mag);
        return mag;
    };
    cv::Mat d = edges(m) - edges(s);
    cv::Mat d2 = d.mul(d);
    return cv::mean(d2, valid)[0];
}

}  // namespace

RegistrationMethod parse_registration_method(std::string_view text) {
    if (text == "none") return RegistrationMethod::None;
    if (text == "auto") return RegistrationMethod::Auto;
    if (text == "control-points") return RegistrationMethod::ControlPoints;
    if (text == "camera-model") return RegistrationMethod::CameraModel;
    fail("registration method '{}': expected one of none, auto, control-points, camera-model",
         text);
}

std::string to_string(RegistrationMethod method) {
    switch (method) {
        case RegistrationMethod::None:
            return "none";
        case RegistrationMethod::Auto:
            return "auto";
        case RegistrationMethod::ControlPoints:
            return "control-points";
        case RegistrationMethod::CameraModel:
            return "camera-model";
    }
    return "?";
}

std::vector<TiePoint> load_control_points(const std::filesystem::path& path) {
    const ConfigNode root = ConfigNode::load_file(path);
    if (!root.is_sequence())
        root.fail("expected a list of {measured: [x, y], simulated: [x, y]} pairs");
    std::vector<TiePoint> points;
    for (const auto& item : root.elements()) {
        if (!item.is_map()) item.fail("expected a mapping {measured: [x, y], simulated: [x, y]}");
        item.check_keys({"measured", "simulated"});
        auto point = [&](std::string_view key) {
            const ConfigNode node = item.at(key);
            const auto xy = node.as<std::vector<double>>();
            if (xy.size() != 2 || !std::isfinite(xy[0]) || !std::isfinite(xy[1]))
                node.fail("expected a point [x, y] in pixels (two finite numbers)");
            return PixelPoint{xy[0], xy[1]};
        };
        points.push_back({point("measured"), point("simulated")});
    }
    return points;
}

Registration register_images(const Image& measured, const Image& simulated,
                             RegistrationMethod method, const std::vector<TiePoint>& control_points,
                             const std::atomic<bool>* cancel) {
    const int w = measured.width(), h = measured.height();
    const bool same_size = w == simulated.width() && h == simulated.height();
    Registration reg;
    reg.method = method;
    cv::Matx33d homography = cv::Matx33d::eye();

    if (method == RegistrationMethod::CameraModel)
        fail("registration 'camera-model' needs the measured camera's model (--camera CAM.yaml)");
    if (method == RegistrationMethod::None) {
        if (!same_size)
            fail(
                "the measured image is {}×{} and the simulated one {}×{}: registration 'none' "
                "needs equal sizes; "
                "use --registration auto or give control points (--control-points CP.yaml)",
                w, h, simulated.width(), simulated.height());
        reg.note = "no registration requested: pixel grids compared as they are";
    } else if (method == RegistrationMethod::ControlPoints) {
        if (control_points.size() < 4)
            fail(
                "control points: a homography needs at least 4 pairs measured (x, y) ↔ simulated "
                "(x, y), got {}",
                control_points.size());
        std::vector<cv::Point2d> src, dst;
        for (const auto& cp : control_points) {
            src.emplace_back(cp.measured.x, cp.measured.y);
            dst.emplace_back(cp.simulated.x, cp.simulated.y);
        }
        const cv::Mat hm = cv::findHomography(src, dst, 0);
        if (hm.empty())
            fail(
                "control points: no homography fits the {} pairs (are the points collinear or "
                "repeated?)",
                control_points.size());
        homography = cv::Matx33d(hm);
        double sum2 = 0.0;
        for (std::size_t i = 0; i < src.size(); ++i) {
            const cv::Point2d e = apply(homography, src[i]) - dst[i];
            sum2 += e.dot(e);
        }
        reg.control_point_rms_px = std::sqrt(sum2 / static_cast<double>(src.size()));
        reg.model = "homography";
        reg.note = fmt::format("homography from {} control points", control_points.size());
    } else {
        const double aspect_m = static_cast<double>(w) / h;
        const double aspect_s = static_cast<double>(simulated.width()) / simulated.height();
        if (!same_size && std::abs(aspect_m / aspect_s - 1.0) > 0.01)
            fail(
                "the measured image is {}×{} (aspect {:.3f}) and the simulated one {}×{} (aspect "
                "{:.3f}): automatic "
                "registration needs equal aspect ratios; give control points (--control-points "
                "CP.yaml with ≥ 4 "
                "pairs measured (x, y) ↔ simulated (x, y))",
                w, h, aspect_m, simulated.width(), simulated.height(), aspect_s);
        const cv::Mat m_s0 = plane(measured, "S0");
        cv::Mat templ = gradient_magnitude(m_s0);
        cv::Mat input = gradient_magnitude(plane(simulated, "S0"));
        // Measured grid → resized simulated grid → simulated grid (pixel centres map to pixel
        // centres).
        cv::Matx33d prescale = cv::Matx33d::eye();
        if (!same_size) {
            const double kx = static_cast<double>(simulated.width()) / w,
                         ky = static_cast<double>(simulated.height()) / h;
            cv::resize(input, input, templ.size(), 0, 0, cv::INTER_AREA);
            prescale = cv::Matx33d(kx, 0, 0.5 * kx - 0.5, 0, ky, 0.5 * ky - 0.5, 0, 0, 1);
        }
        const EccOutcome ecc = ecc_register(templ, input, finite_mask(m_s0), cancel);
        homography = prescale * ecc.h;
        reg.ecc_correlation = ecc.correlation;
        reg.model = motion_name(ecc.motion);
        reg.note =
            ecc.note.empty() ? fmt::format("ECC {} on S0 gradient magnitude", reg.model) : ecc.note;
        if (!same_size)
            reg.note += fmt::format("; simulated {}×{} resized to {}×{} first", simulated.width(),
                                    simulated.height(), w, h);
        if (same_size) {
            // Keep the pixel grids as they are unless the warp matches the edges significantly
            // better.
            cv::Mat warped = plane(simulated, "S0");
            cv::warpPerspective(warped.clone(), warped, homography, warped.size(),
                                cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_CONSTANT,
                                cv::Scalar(kNaN));
            cv::Mat valid =
                finite_mask(m_s0) & finite_mask(plane(simulated, "S0")) & finite_mask(warped);
            cv::erode(valid, valid, cv::getStructuringElement(cv::MORPH_RECT, {13, 13}));
            const double displacement = max_corner_displacement(homography, w, h);
            if (cv::countNonZero(valid) >= 64) {
                reg.identity_edge_mismatch =
                    edge_mismatch(measured, simulated, cv::Matx33d::eye(), valid);
                reg.registered_edge_mismatch =
                    edge_mismatch(measured, simulated, homography, valid);
            }
            const bool improves =
                reg.identity_edge_mismatch && reg.registered_edge_mismatch &&
                *reg.registered_edge_mismatch <
                    (1.0 - kRegistrationMinImprovement) * *reg.identity_edge_mismatch;
            if (displacement < 0.05 || !improves) {
                const std::string found =
                    fmt::format("ECC found a {} moving the corners by up to {:.2f} px", reg.model,
                                displacement);
                homography = cv::Matx33d::eye();
                reg.model = "identity";
                reg.note =
                    displacement < 0.05 ? "images already match (ECC displacement < 0.05 px "
                                          "everywhere): identity used"
                    : reg.identity_edge_mismatch && reg.registered_edge_mismatch
                        ? fmt::format(
                              "images already aligned: {}, but it reduces the S0 edge mismatch by "
                              "only "
                              "{:.1f} % (< {:.0f} %), so the pixel grids are compared as they are",
                              found,
                              100.0 * (1.0 -
                                       *reg.registered_edge_mismatch / *reg.identity_edge_mismatch),
                              100.0 * kRegistrationMinImprovement)
                        : fmt::format(
                              "{}, but too few valid pixels to show it improves the match: "
                              "identity used",
                              found);
            } else {
                reg.note += fmt::format(
                    "; reduces the S0 edge mismatch by {:.1f} % against identity",
                    100.0 * (1.0 - *reg.registered_edge_mismatch / *reg.identity_edge_mismatch));
            }
        }
    }
    reg.measured_to_simulated = to_array(homography);
    if (reg.model != "identity") {
        reg.max_corner_displacement_px = max_corner_displacement(homography, w, h);
        reg.rotation_deg = rotation_deg(homography, w, h);
    }
    reg.residual_shift_px = residual_shift(measured, resample_to_measured(simulated, reg, w, h));
    return reg;
}

namespace {

/// The renderer's lens `values` (its `what`, from the simulated image's header), checked against
/// `expected` to float precision.
void check_camera_attribute(const std::optional<std::vector<double>>& values,
                            const std::vector<double>& expected, const std::string& camera_name,
                            const std::string& what) {
    if (!values)
        fail(
            "registration by camera model {}: the simulated image's header has no camera {}; "
            "render it through "
            "that model (scene `camera: {{model: {}}}`) with this version of tirpol",
            camera_name, what, camera_name);
    // Missing trailing coefficients are zero (the renderer writes the shortest OpenCV layout that
    // holds them).
    const auto at = [](const std::vector<double>& v, std::size_t i) {
        return i < v.size() ? v[i] : 0.0;
    };
    bool same = true;
    for (std::size_t i = 0; same && i < std::max(values->size(), expected.size()); ++i)
        same = std::abs(at(*values, i) - at(expected, i)) <=
               1e-6 * std::max(std::abs(at(expected, i)), 1e-3);
    if (!same)
        fail(
            "registration by camera model {}: the simulated image was rendered with {} [{}], the "
            "model has [{}]; "
            "render the simulation through the same camera model",
            camera_name, what, fmt::join(*values, ", "), fmt::join(expected, ", "));
}

}  // namespace

Registration register_by_camera_model(const Image& measured, const Image& simulated,
                                      const CameraModel& camera, const std::string& camera_name) {
    const int w = measured.width(), h = measured.height();
    if (w != camera.width || h != camera.height)
        fail("registration by camera model {}: the model is {}×{} pixels, the measured image {}×{}",
             camera_name, camera.width, camera.height, w, h);
    if (simulated.width() != w || simulated.height() != h)
        fail(
            "registration by camera model {}: the simulated image is {}×{}, the model and the "
            "measured image {}×{}",
            camera_name, simulated.width(), simulated.height(), w, h);
    const StokesImageHeader header = read_stokes_image_header(simulated, "the simulated image");
    std::optional<std::vector<double>> intrinsics;
    if (const auto& k = header.camera_intrinsics_px) intrinsics.emplace(k->begin(), k->end());
    check_camera_attribute(intrinsics, {camera.fx, camera.fy, camera.cx, camera.cy}, camera_name,
                           "intrinsics fx fy cx cy");
    check_camera_attribute(header.camera_distortion, camera.distortion, camera_name, "distortion");
    Registration reg;
    reg.method = RegistrationMethod::CameraModel;
    reg.note = fmt::format(
        "simulation rendered through the calibrated camera model {} (fx {:.2f} fy {:.2f} cx {:.2f} "
        "cy {:.2f} px, {} "
        "distortion): it lies on the measured pixel grid, no warp",
        camera_name, camera.fx, camera.fy, camera.cx, camera.cy, camera.distortion_model());
    reg.residual_shift_px = residual_shift(measured, simulated);
    return reg;
}

Image resample_to_measured(const Image& simulated, const Registration& registration, int width,
                           int height) {
    if (registration.model == "identity" && simulated.width() == width &&
        simulated.height() == height)
        return simulated;
    Image out(width, height);
    out.attributes() = simulated.attributes();
    const cv::Matx33d h = to_matx(registration.measured_to_simulated);
    // Bilinear interpolation with weights w_k of independent samples of variance v has variance
    // Σ w_k² v, not Σ w_k v: for locally constant v that is the interpolated variance times
    // ((1−fx)² + fx²)((1−fy)² + fy²), with (fx, fy) the fractional source position.
    std::vector<float> variance_factor(static_cast<std::size_t>(width) *
                                       static_cast<std::size_t>(height));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const cv::Point2d src = apply(h, {static_cast<double>(x), static_cast<double>(y)});
            const double fx = src.x - std::floor(src.x), fy = src.y - std::floor(src.y);
            variance_factor[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                            static_cast<std::size_t>(x)] =
                static_cast<float>(((1 - fx) * (1 - fx) + fx * fx) *
                                   ((1 - fy) * (1 - fy) + fy * fy));
        }
    auto ends_with = [](const std::string& name, std::string_view suffix) {
        return name.size() > suffix.size() &&
               name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
    };
    for (const auto& name : simulated.channel_names()) {
        const bool label = name == "object_id" || name == "material_id";
        cv::Mat dst;
        cv::warpPerspective(plane(simulated, name), dst, h, {width, height},
                            (label ? cv::INTER_NEAREST : cv::INTER_LINEAR) | cv::WARP_INVERSE_MAP,
                            cv::BORDER_CONSTANT, cv::Scalar(kNaN));
        std::vector<float> data(dst.ptr<float>(), dst.ptr<float>() + dst.total());
        if (ends_with(name, "_var"))
            for (std::size_t i = 0; i < data.size(); ++i) data[i] *= variance_factor[i];
        else if (ends_with(name, "_std"))
            for (std::size_t i = 0; i < data.size(); ++i) data[i] *= std::sqrt(variance_factor[i]);
        out.set_channel(name, std::move(data));
    }
    return out;
}

}  // namespace tirpol::report
