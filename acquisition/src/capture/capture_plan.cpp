#include "tirpol/acquisition/capture_plan.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "drift_reference_plan.h"
#include "tirpol/acquisition/internal/angles.h"
#include "tirpol/core/error.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::acquisition {

namespace {

/// YAML → JSON for free-form metadata: numbers stay numbers, true/false stay booleans.
nlohmann::json yaml_to_json(const ConfigNode& node) {
    if (node.is_map()) {
        nlohmann::json j = nlohmann::json::object();
        for (const auto& key : node.keys()) j[key] = yaml_to_json(node.at(key));
        return j;
    }
    if (node.is_sequence()) {
        nlohmann::json j = nlohmann::json::array();
        for (const auto& e : node.elements()) j.push_back(yaml_to_json(e));
        return j;
    }
    if (node.is_null()) return nullptr;
    const auto text = node.as<std::string>();
    try {
        std::size_t used = 0;
        const double v = std::stod(text, &used);
        if (used == text.size() && std::isfinite(v)) return v;
    } catch (const std::exception&) {
    }
    if (text == "true") return true;
    if (text == "false") return false;
    return text;
}

/// An integer in [1, max]; the upper limit stops a typo (`0x7fffffff`) from starting a run that
/// never ends.
int count_in_range(const ConfigNode& root, std::string_view key, int fallback, int max) {
    const int v = root.get_or<int>(key, fallback);
    if (v < 1 || v > max)
        root.at(key).fail(fmt::format("expected an integer ≥ 1 and ≤ {}, got {}", max, v));
    return v;
}

/// A duration in seconds in [0, max_s] (or (0, max_s]); `settle_s: 4294967296` would sleep for 136
/// years.
double seconds_in_range(const ConfigNode& root, std::string_view key, double fallback,
                        bool allow_zero, double max_s) {
    if (!root.has(key)) return fallback;
    const double v = root.get<double>(key);
    if (!(allow_zero ? v >= 0.0 : v > 0.0) || !(v <= max_s))
        root.at(key).fail(fmt::format("expected a duration in seconds {} 0 and ≤ {}, got {}",
                                      allow_zero ? "≥" : ">", max_s, v));
    return v;
}

/// A polarizer angle in [0, 360): a value outside is refused rather than wrapped, since 405 or −45
/// is more often a typo than a wish, and the session records the angle as written.
double plan_angle(const ConfigNode& node, double angle_deg) {
    if (!std::isfinite(angle_deg) || angle_deg < 0.0 || angle_deg >= 360.0) {
        const std::string hint =
            std::isfinite(angle_deg)
                ? fmt::format(" (the same position is {:g}°)", wrap_degrees(angle_deg))
                : "";
        node.fail(fmt::format("angle {}° is outside [0, 360){}", angle_deg, hint));
    }
    return angle_deg;
}

std::vector<double> temperatures(const ConfigNode& ref) {
    if (ref.has("temperatures_k") && ref.has("temperatures_c"))
        ref.fail("give temperatures_k or temperatures_c, not both");
    std::vector<double> out;
    if (ref.has("temperatures_k")) out = ref.get<std::vector<double>>("temperatures_k");
    if (ref.has("temperatures_c"))
        for (double c : ref.get<std::vector<double>>("temperatures_c"))
            out.push_back(c + kZeroCelsiusK);
    for (double t : out)
        if (!(t > 0.0 && t < 2000.0))
            ref.fail(fmt::format("temperature {} K is not a blackbody temperature (0–2000 K)", t));
    return out;
}

/// A number in [lo, hi] under `node[key]`, `fallback` when absent.
double number_in_range(const ConfigNode& node, std::string_view key, double fallback, double lo,
                       double hi) {
    return node.has(key) ? node.get_in_range(key, lo, hi) : fallback;
}

BlackbodyStabilityCriterion stability_criterion(const ConfigNode& node) {
    if (!node.is_map())
        node.fail("expected a mapping {tolerance_k, stable_for_s, timeout_s, poll_s}");
    node.check_keys({"tolerance_k", "stable_for_s", "timeout_s", "poll_s"});
    BlackbodyStabilityCriterion c;
    c.tolerance_k = number_in_range(node, "tolerance_k", c.tolerance_k, 1e-4, 50.0);
    c.stable_for_s = number_in_range(node, "stable_for_s", c.stable_for_s, 0.0, kMaxSettleSeconds);
    c.timeout_s = number_in_range(node, "timeout_s", c.timeout_s, 1e-3, 24 * 3600.0);
    c.poll_s = number_in_range(node, "poll_s", c.poll_s, 0.01, 600.0);
    return c;
}

nlohmann::json criterion_json(const BlackbodyStabilityCriterion& c) {
    return {{"tolerance_k", c.tolerance_k},
            {"stable_for_s", c.stable_for_s},
            {"timeout_s", c.timeout_s},
            {"poll_s", c.poll_s}};
}

}  // namespace

CapturePlan CapturePlan::parse(const ConfigNode& root) {
    // An empty file (or one holding only comments) is almost always the wrong file, not a wish for
    // the default plan.
    if (root.is_null() || (root.is_map() && root.keys().empty()))
        root.fail(
            "the capture plan is empty; write at least one field (e.g. `frames_per_angle: 16`), "
            "the others take their "
            "defaults");
    root.check_keys({"angles_deg", "frames_per_angle", "settle_s", "repeats", "angle_tolerance_deg",
                     "move_timeout_s", "home_timeout_s", "frame_timeout_s", "references",
                     "scene_reference", "shutter_interleave", "metadata", "approach_overshoot_deg",
                     "home_check_every"});
    CapturePlan plan;
    if (root.has("angles_deg")) {
        plan.angles_deg = root.get<std::vector<double>>("angles_deg");
        if (plan.angles_deg.empty()) root.at("angles_deg").fail("expected at least one angle");
        for (double a : plan.angles_deg) plan_angle(root.at("angles_deg"), a);
        for (std::size_t i = 0; i < plan.angles_deg.size(); ++i)
            for (std::size_t k = 0; k < i; ++k)
                if (std::abs(angle_difference_deg(plan.angles_deg[i], plan.angles_deg[k])) < 1e-9)
                    root.at("angles_deg")
                        .fail(fmt::format("angle {}° is listed twice", plan.angles_deg[i]));
    }
    plan.frames_per_angle =
        count_in_range(root, "frames_per_angle", plan.frames_per_angle, kMaxFramesPerStep);
    plan.repeats = count_in_range(root, "repeats", plan.repeats, kMaxRepeats);
    plan.settle_s = seconds_in_range(root, "settle_s", plan.settle_s, true, kMaxSettleSeconds);
    plan.move_timeout_s = seconds_in_range(root, "move_timeout_s", plan.move_timeout_s, false,
                                           kMaxMoveTimeoutSeconds);
    plan.home_timeout_s = seconds_in_range(root, "home_timeout_s", plan.home_timeout_s, false,
                                           kMaxMoveTimeoutSeconds);
    plan.frame_timeout_s = seconds_in_range(root, "frame_timeout_s", plan.frame_timeout_s, false,
                                            kMaxFrameTimeoutSeconds);
    if (root.has("angle_tolerance_deg"))
        plan.angle_tolerance_deg = root.get_in_range("angle_tolerance_deg", 1e-6, 10.0);
    if (root.has("approach_overshoot_deg"))
        plan.approach_overshoot_deg = root.get_in_range("approach_overshoot_deg", 0.0, 90.0);
    if (root.has("home_check_every"))
        plan.home_check_every = count_in_range(root, "home_check_every", 1, kMaxRepeats);
    if (auto refs = root.find("references")) {
        for (const auto& ref : refs->elements()) {
            ref.check_keys({"kind", "temperatures_k", "temperatures_c", "frames", "angle_deg",
                            "angles_deg", "controller"});
            ReferenceSpec spec;
            const auto kind_text = ref.get<std::string>("kind");
            const auto kind = record_kind_from_string(kind_text);
            if (!kind || *kind == RecordKind::Polarizer)
                ref.at("kind").fail(
                    fmt::format("expected blackbody or shutter, got '{}'", kind_text));
            spec.kind = *kind;
            spec.temperatures_k = temperatures(ref);
            if (spec.kind == RecordKind::Blackbody && spec.temperatures_k.empty())
                ref.fail("a blackbody reference needs temperatures_k (or temperatures_c)");
            spec.frames = count_in_range(ref, "frames", spec.frames, kMaxFramesPerStep);
            if (ref.has("angle_deg"))
                spec.angle_deg = plan_angle(ref.at("angle_deg"), ref.get<double>("angle_deg"));
            if (ref.has("angles_deg")) {
                if (ref.has("angle_deg")) ref.fail("give angle_deg or angles_deg, not both");
                spec.angles_deg = ref.get<std::vector<double>>("angles_deg");
                if (spec.angles_deg.empty())
                    ref.at("angles_deg").fail("expected at least one angle");
                for (double a : spec.angles_deg) plan_angle(ref.at("angles_deg"), a);
            }
            if (auto c = ref.find("controller")) {
                if (spec.kind != RecordKind::Blackbody)
                    c->fail("only a blackbody reference has a controller");
                spec.controller = stability_criterion(*c);
            }
            plan.references.push_back(std::move(spec));
        }
    }
    detail::parse_drift_references(root, plan);
    if (plan.approach_overshoot_deg > 0)
        for (const auto& step : plan_steps(plan))
            if (step.angle_deg + plan.approach_overshoot_deg >= 360.0)
                root.at("approach_overshoot_deg")
                    .fail(fmt::format("{} ({}) approaches from {}°, past a full turn; the "
                                      "one-direction approach needs every angle + overshoot "
                                      "below 360°",
                                      step.label, step.angle_deg,
                                      step.angle_deg + plan.approach_overshoot_deg));
    if (auto meta = root.find("metadata")) {
        if (!meta->is_map()) meta->fail("expected a mapping of free-form fields");
        plan.metadata = yaml_to_json(*meta);
    }
    return plan;
}

CapturePlan CapturePlan::load(const std::filesystem::path& path) {
    return parse(ConfigNode::load_file(path));
}

nlohmann::json CapturePlan::to_json() const {
    nlohmann::json refs = nlohmann::json::array();
    for (const auto& r : references) {
        nlohmann::json ref = {{"kind", tirpol::to_string(r.kind)},
                              {"temperatures_k", r.temperatures_k},
                              {"frames", r.frames},
                              {"angle_deg", r.angle_deg}};
        // Only when given: a plan without them keeps the JSON (and so --resume) of earlier
        // versions.
        if (!r.angles_deg.empty()) ref["angles_deg"] = r.angles_deg;
        if (r.controller) ref["controller"] = criterion_json(*r.controller);
        refs.push_back(std::move(ref));
    }
    nlohmann::json out = {{"angles_deg", angles_deg},
                          {"frames_per_angle", frames_per_angle},
                          {"settle_s", settle_s},
                          {"repeats", repeats},
                          {"angle_tolerance_deg", angle_tolerance_deg},
                          {"move_timeout_s", move_timeout_s},
                          {"home_timeout_s", home_timeout_s},
                          {"frame_timeout_s", frame_timeout_s},
                          {"references", refs}};
    detail::drift_references_json(*this, out);
    // Only when set, as above: earlier plans keep their JSON.
    if (approach_overshoot_deg > 0) out["approach_overshoot_deg"] = approach_overshoot_deg;
    if (home_check_every > 0) out["home_check_every"] = home_check_every;
    return out;
}

bool plan_uses_blackbody_controller(const CapturePlan& plan) {
    return std::any_of(plan.references.begin(), plan.references.end(),
                       [](const ReferenceSpec& r) { return r.controller.has_value(); });
}

std::vector<CaptureStep> plan_steps(const CapturePlan& plan) {
    std::vector<CaptureStep> steps;
    auto add = [&](CaptureStep s, const std::string& stem) {
        s.index = steps.size();
        s.file = session_frame_file(fmt::format("s{:03}_{}", s.index, stem));
        steps.push_back(std::move(s));
    };
    for (const auto& ref : plan.references) {
        const std::vector<std::optional<double>> temps =
            ref.temperatures_k.empty() ? std::vector<std::optional<double>>{std::nullopt}
                                       : std::vector<std::optional<double>>(
                                             ref.temperatures_k.begin(), ref.temperatures_k.end());
        const bool per_angle = !ref.angles_deg.empty();
        const std::vector<double> angles =
            per_angle ? ref.angles_deg : std::vector<double>{ref.angle_deg};
        for (const auto& t : temps)
            for (double a : angles) {
                CaptureStep s;
                s.kind = ref.kind;
                s.angle_deg = a;
                s.temperature_k = t;
                s.blackbody_control = ref.controller;
                s.frames = ref.frames;
                const std::string what = ref.kind == RecordKind::Blackbody ? "bb" : "shutter";
                std::string label =
                    t ? fmt::format("{} at {:.2f} K", tirpol::to_string(ref.kind), *t)
                      : std::string(tirpol::to_string(ref.kind));
                std::string stem = t ? fmt::format("{}_{:.2f}K", what, *t) : what;
                if (per_angle) {
                    label += fmt::format(", polarizer {:g}°", a);
                    stem += fmt::format("_pol_{:07.3f}deg", a);
                }
                s.label = std::move(label);
                add(s, stem);
            }
    }
    // Interleaved shutters stay at the polarizer angle of the scene step next to them: no extra
    // move.
    const ShutterInterleaveSpec* interleave =
        plan.shutter_interleave ? &*plan.shutter_interleave : nullptr;
    int scene_steps = 0, shutters = 0;
    auto add_shutter = [&](double angle_deg) {
        add(detail::interleaved_shutter_step(*interleave, shutters, angle_deg),
            fmt::format("shutter_i{:03}", shutters));
        ++shutters;
    };
    for (int r = 0; r < plan.repeats; ++r)
        for (double a : plan.angles_deg) {
            CaptureStep s;
            s.kind = RecordKind::Polarizer;
            s.angle_deg = a;
            s.repeat = r;
            if (interleave && scene_steps++ % interleave->every == 0) {
                add_shutter(a);
                s.after_shutter = true;
            }
            s.frames = plan.frames_per_angle;
            s.label = plan.repeats > 1
                          ? fmt::format("polarizer {:g}° (repeat {}/{})", a, r + 1, plan.repeats)
                          : fmt::format("polarizer {:g}°", a);
            add(s, fmt::format("pol_{:07.3f}deg_r{}", a, r));
        }
    if (interleave && !steps.empty()) add_shutter(steps.back().angle_deg);
    return steps;
}

}  // namespace tirpol::acquisition
