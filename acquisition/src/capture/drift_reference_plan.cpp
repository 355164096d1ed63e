#include "drift_reference_plan.h"

#include <fmt/format.h>

#include "tirpol/core/radiometry.h"

namespace tirpol::acquisition::detail {

namespace {
/// temperature_k or temperature_c (not both) under `node`, as kelvin.
std::optional<double> temperature(const ConfigNode& node) {
    if (node.has("temperature_k") && node.has("temperature_c"))
        node.fail("give temperature_k or temperature_c, not both");
    if (node.has("temperature_k")) return node.get_in_range("temperature_k", 1.0, 2000.0);
    if (node.has("temperature_c"))
        return node.get_in_range("temperature_c", -272.0, 1700.0) + kZeroCelsiusK;
    return std::nullopt;
}

int pixels(const ConfigNode& roi, std::string_view key, double lo) {
    const double v = roi.get_in_range(key, lo, 1e6);
    if (v != static_cast<double>(static_cast<int>(v)))
        roi.at(key).fail("expected a whole number of pixels");
    return static_cast<int>(v);
}
}  // namespace

void parse_drift_references(const ConfigNode& root, CapturePlan& plan) {
    if (auto node = root.find("scene_reference")) {
        node->check_keys({"roi", "temperature_k", "temperature_c", "temperature_sigma_k"});
        const ConfigNode roi = node->at("roi");
        roi.check_keys({"x", "y", "width", "height"});
        SceneReferenceSpec spec{pixels(roi, "x", 0),
                                pixels(roi, "y", 0),
                                pixels(roi, "width", 1),
                                pixels(roi, "height", 1),
                                0.0,
                                0.0};
        const auto t = temperature(*node);
        if (!t)
            node->fail(
                "the reference blackbody needs temperature_k (or temperature_c): its "
                "contact-sensor value");
        spec.temperature_k = *t;
        if (node->has("temperature_sigma_k"))
            spec.temperature_sigma_k = node->get_in_range("temperature_sigma_k", 0.0, 50.0);
        plan.scene_reference = spec;
    }
    if (auto node = root.find("shutter_interleave")) {
        node->check_keys({"every", "temperature_k", "temperature_c", "frames"});
        ShutterInterleaveSpec spec;
        spec.every = static_cast<int>(node->get_in_range("every", 1, kMaxRepeats));
        spec.temperature_k = temperature(*node);
        if (node->has("frames"))
            spec.frames = static_cast<int>(node->get_in_range("frames", 1, kMaxFramesPerStep));
        plan.shutter_interleave = spec;
    }
}

void drift_references_json(const CapturePlan& plan, nlohmann::json& out) {
    if (const auto& r = plan.scene_reference)
        out["scene_reference"] = {
            {"roi", {{"x", r->x}, {"y", r->y}, {"width", r->width}, {"height", r->height}}},
            {"temperature_k", r->temperature_k},
            {"temperature_sigma_k", r->temperature_sigma_k}};
    if (const auto& s = plan.shutter_interleave) {
        out["shutter_interleave"] = {{"every", s->every}, {"frames", s->frames}};
        if (s->temperature_k) out["shutter_interleave"]["temperature_k"] = *s->temperature_k;
    }
}

CaptureStep interleaved_shutter_step(const ShutterInterleaveSpec& spec, int index,
                                     double angle_deg) {
    CaptureStep s;
    s.kind = RecordKind::Shutter;
    s.angle_deg = angle_deg;
    s.temperature_k = spec.temperature_k;
    s.frames = spec.frames;
    s.label = spec.temperature_k ? fmt::format("shutter {} (interleaved) at {:.2f} K", index + 1,
                                               *spec.temperature_k)
                                 : fmt::format("shutter {} (interleaved)", index + 1);
    return s;
}

}  // namespace tirpol::acquisition::detail
