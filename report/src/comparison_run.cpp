#include <fmt/format.h>

#include <cmath>

#include "tirpol/core/camera_model.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/report/comparison_report.h"

namespace tirpol::report {

namespace {
template <typename... Args>
[[noreturn]] void refuse(const std::string& option, fmt::format_string<Args...> format,
                         Args&&... args) {
    throw OptionValueError(option, fmt::format(format, std::forward<Args>(args)...));
}

// Default: the camera model when given, else control points when given, else automatic.
RegistrationMethod registration_of(const ComparisonRunOptions& o) {
    RegistrationMethod method = !o.camera_model.empty()     ? RegistrationMethod::CameraModel
                                : !o.control_points.empty() ? RegistrationMethod::ControlPoints
                                                            : RegistrationMethod::Auto;
    if (!o.registration.empty()) {
        try {
            method = parse_registration_method(o.registration);
        } catch (const Error& e) {
            throw OptionValueError("--registration", e.what());
        }
    }
    if (method == RegistrationMethod::ControlPoints && o.control_points.empty())
        refuse("--registration", "control-points needs --control-points CP.yaml");
    if (method == RegistrationMethod::CameraModel && o.camera_model.empty())
        refuse("--registration", "camera-model needs --camera CAM.yaml");
    if (!o.camera_model.empty() && method != RegistrationMethod::CameraModel)
        refuse("--camera",
               "a camera model registers by the model: leave out --registration or give "
               "camera-model");
    return method;
}

void check_values(const ComparisonRunOptions& o) {
    if (o.measured_frame_sigma &&
        (!(*o.measured_frame_sigma > 0.0) || !std::isfinite(*o.measured_frame_sigma)))
        refuse("--measured-sigma", "expected a positive radiance in W/(m²·sr), got {}",
               *o.measured_frame_sigma);
    if (!(o.gain_sigma_relative >= 0.0 && o.gain_sigma_relative < 1.0))
        refuse("--gain-sigma", "expected a relative gain uncertainty in [0, 1), got {}",
               o.gain_sigma_relative);
    if (!(o.offset_sigma >= 0.0) || !std::isfinite(o.offset_sigma))
        refuse("--offset-sigma", "expected a non-negative radiance in W/(m²·sr), got {}",
               o.offset_sigma);
    if (!(o.false_alarm > 0.0 && o.false_alarm < 0.5))
        refuse("--false-alarm", "expected a probability in (0, 0.5), got {}", o.false_alarm);
    if (!(o.power > 0.5 && o.power < 1.0))
        refuse("--power", "expected a probability in (0.5, 1), got {}", o.power);
    if (!o.band_um.empty() && o.band_um.size() != 2)
        refuse("--band-um", "expected two values LO HI, got {}", o.band_um.size());
}
}  // namespace

CompareResult run_comparison(const ComparisonRunOptions& o) {
    CompareOptions options;
    options.measured_name = o.measured;
    options.simulated_name = o.simulated;
    if (!o.control_points.empty()) options.control_points = load_control_points(o.control_points);
    if (!o.camera_model.empty()) {
        options.camera_model = read_camera_model(o.camera_model);
        options.camera_model_name = o.camera_model;
    }
    options.registration = registration_of(o);
    if (!o.regions.empty()) options.regions = load_regions(o.regions);
    check_values(o);
    options.measured_frame_sigma = o.measured_frame_sigma;
    options.measured_gain_sigma_relative = o.gain_sigma_relative;
    options.measured_offset_sigma = o.offset_sigma;
    options.design.false_alarm_per_region = o.false_alarm;
    options.design.power = o.power;
    if (!o.band_um.empty()) options.band_um = std::array<double, 2>{o.band_um[0], o.band_um[1]};
    OutputGuard()
        .input(o.measured, "--measured")
        .input(o.simulated, "--simulated")
        .input(o.regions, "--rois")
        .input(o.control_points, "--control-points")
        .input(o.camera_model, "--camera")
        .output_folder(o.output, "--output",
                       {"report.html", "report.json", "comparison.exr", "*.png", "*.svg"})
        .check(o.force);
    const Image measured = read_exr(o.measured);
    const Image simulated = read_exr(o.simulated);
    Provenance& provenance = options.provenance;
    provenance.tool_version = o.tool_version;
    provenance.command_line = o.command_line;
    provenance.inputs.push_back(describe_input("measured", o.measured, &measured));
    provenance.inputs.push_back(describe_input("simulated", o.simulated, &simulated));
    if (!o.regions.empty()) provenance.inputs.push_back(describe_input("regions", o.regions));
    if (!o.control_points.empty())
        provenance.inputs.push_back(describe_input("control points", o.control_points));
    if (!o.camera_model.empty())
        provenance.inputs.push_back(describe_input("camera model", o.camera_model));
    return write_comparison_report(measured, simulated, options, o.output);
}

}  // namespace tirpol::report
