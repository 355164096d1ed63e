#pragma once
/// \file capture_plan.h
/// The capture plan (YAML, written by people) and the ordered steps it expands to. Example:
/// ```yaml
/// angles_deg: [0, 45, 90, 135]   # polarizer angles (default)
/// frames_per_angle: 16
/// settle_s: 0.5                  # wait after each move before grabbing
/// repeats: 1                     # the whole angle set, this many times
/// angle_tolerance_deg: 0.05      # read-back must agree with the request this well
/// move_timeout_s: 60
/// home_timeout_s: 120
/// frame_timeout_s: 5
/// approach_overshoot_deg: 2      # optional: every move arrives from above, via target + this
/// home_check_every: 4            # optional: home-sensor check every N cycles and at the end
/// references:                    # optional, taken before the polarizer steps
///   - kind: blackbody
///     temperatures_k: [293.15, 313.15]    # or temperatures_c
///     frames: 32
///   - kind: shutter
///     frames: 16
///   - kind: blackbody               # set by a blackbody controller (tirpol acquire --blackbody
///   URI)
///     temperatures_c: [10, 20, 30, 40]
///     frames: 32
///     angles_deg: [0, 45, 90, 135]  # optional: each set-point × these polarizer angles
///     controller: {tolerance_k: 0.05, stable_for_s: 30, timeout_s: 1800, poll_s: 1}
/// scene_reference:               # optional: in-scene reference blackbody region (drift
/// correction)
///   roi: {x: 2, y: 2, width: 6, height: 6}   # pixels
///   temperature_k: 303.15         # or temperature_c: its contact sensor
///   temperature_sigma_k: 0.02
/// shutter_interleave:             # optional: a shutter record before every N scene records and at
/// the end
///   every: 4
///   temperature_k: 295.0          # the shutter's sensor (needed for the drift correction)
///   frames: 16
/// metadata: {site: roof, operator: ..., targets: [...], polarizer_tilt_deg: 5,
/// air_temperature_c: 4.5}
/// ```
/// Unknown keys are errors naming the key (typos never pass silently); so are an empty plan file,
/// angles outside [0, 360) and values beyond the limits below, all before any device moves.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/core/config.h"
#include "tirpol/core/session.h"

namespace tirpol::acquisition {

/// Upper limits of a plan's fields: far above any real use, low enough that a typo fails at once
/// instead of starting a run that never ends.
inline constexpr int kMaxFramesPerStep = 100000;  ///< frames_per_angle, references[].frames
inline constexpr int kMaxRepeats = 10000;
inline constexpr double kMaxSettleSeconds = 3600.0;
inline constexpr double kMaxMoveTimeoutSeconds = 3600.0;  ///< move_timeout_s, home_timeout_s
inline constexpr double kMaxFrameTimeoutSeconds = 600.0;

/// When a set-point counts as reached (capture plan `references[].controller`).
struct BlackbodyStabilityCriterion {
    double tolerance_k = 0.1;  ///< |reading − set-point| ≤ tolerance_k ...
    double stable_for_s =
        30.0;  ///< ... with the controller's stability flag set, without a break for this long
    double timeout_s = 1800.0;  ///< then give up: Timeout naming the set-point and the last reading
    double poll_s = 1.0;        ///< controller polling period (also while frames are taken)

    bool operator==(const BlackbodyStabilityCriterion&) const = default;
};

struct ReferenceSpec {
    RecordKind kind = RecordKind::Blackbody;  ///< Blackbody or Shutter
    std::vector<double>
        temperatures_k;  ///< one step per temperature (blackbody: ≥ 1; shutter: optional)
    int frames = 16;
    double angle_deg = 0.0;          ///< where the polarizer sits for the reference frames
    std::vector<double> angles_deg;  ///< instead of angle_deg: every temperature × these angles
    /// Set: a blackbody controller sets each temperature and the frames wait for `controller`'s
    /// criterion (blackbody only); unset: the operator places the blackbody.
    std::optional<BlackbodyStabilityCriterion> controller;
};

/// An in-scene reference blackbody seen in every scene record (docs/calibration.md, "Drift
/// correction").
struct SceneReferenceSpec {
    int x = 0, y = 0, width = 0, height = 0;  ///< ROI, pixels
    double temperature_k = 0.0;               ///< contact-sensor value
    double temperature_sigma_k = 0.0;
};

/// Shutter (flat-field) records interleaved with the scene records.
struct ShutterInterleaveSpec {
    int every = 4;  ///< scene records between two shutter records
    std::optional<double> temperature_k;
    int frames = 16;
};

struct CapturePlan {
    std::vector<double> angles_deg{0.0, 45.0, 90.0, 135.0};
    int frames_per_angle = 16;
    double settle_s = 0.5;
    int repeats = 1;
    double angle_tolerance_deg = 0.05;
    double move_timeout_s = 60.0;
    double home_timeout_s = 120.0;
    double frame_timeout_s = 5.0;
    /// > 0: one-direction approach. Each move first goes to target + overshoot, then down to the
    /// target, so the mount always arrives turning the same way (negative, as homing ends) and the
    /// backlash is taken up on the same side every time. 0: direct moves.
    double approach_overshoot_deg = 0.0;
    /// > 0: before every N-th polarizer cycle and after the last, the stage goes to counted zero
    /// and its home sensor must be active there (Stage::home_sensor_active), else lost steps: the
    /// stage is homed again and the capture fails naming the unverified steps. Encoder stages check
    /// every move through the read-back instead. 0: no home checks.
    int home_check_every = 0;
    std::vector<ReferenceSpec> references;
    std::optional<SceneReferenceSpec> scene_reference;
    std::optional<ShutterInterleaveSpec> shutter_interleave;
    nlohmann::json metadata = nlohmann::json::object();

    /// Parses and validates; throws tirpol::Error naming the file, line and field.
    static CapturePlan parse(const ConfigNode& root);
    static CapturePlan load(const std::filesystem::path& path);
    /// The plan as stored in the session manifest; equal JSON ⇔ same plan (used by --resume).
    nlohmann::json to_json() const;
};

/// One step of the plan: where the stage goes, how many frames, and the record's file name.
struct CaptureStep {
    std::size_t index = 0;
    RecordKind kind = RecordKind::Polarizer;
    double angle_deg = 0.0;
    int repeat = 0;
    std::optional<double> temperature_k;
    std::optional<BlackbodyStabilityCriterion>
        blackbody_control;  ///< the controller sets temperature_k
    int frames = 0;
    std::string file;   ///< "frames/s003_pol_090.000deg_r0.exr"
    std::string label;  ///< "polarizer 90° (repeat 1/2)"
    bool after_shutter =
        false;  ///< a scene step right after an interleaved shutter: reopen it first
};

/// Whether any step needs a blackbody controller.
bool plan_uses_blackbody_controller(const CapturePlan& plan);

/// References first (in plan order; a reference with angles_deg gives temperature × angle steps),
/// then `repeats` × angles, with a shutter step before every shutter_interleave.every of them and
/// one at the end when the plan interleaves shutters. Deterministic: the same plan always
/// gives the same steps and file names, which is what lets --resume skip what is recorded.
std::vector<CaptureStep> plan_steps(const CapturePlan& plan);

}  // namespace tirpol::acquisition
