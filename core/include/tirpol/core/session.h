#pragma once
/// \file session.h
/// The capture-session store: a directory with a `session.json` manifest and one OpenEXR per
/// recorded step under `frames/` (docs/session-format.md).
/// Written by `tirpol acquire`, read by calibration.
///
/// Crash safety: every frame file is written atomically and only then is the manifest rewritten
/// atomically, so after a crash (kill -9, power loss) the manifest lists only complete frames. A
/// frame file that reached the disk but not the manifest is recovered on resume from its own
/// header, which mirrors its record. An existing frame file is never overwritten. (Schema
/// "tirpol.session" version 6; versions 1 to 5 still read.)

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/core/image.h"
#include "tirpol/core/utc_time.h"  // created_utc stamps

namespace tirpol {

inline constexpr const char* kSessionSchema = "tirpol.session";
/// Written by this version. v2 adds each record's `timing` and a measured `camera.frame_rate_hz`;
/// from v2 on `angle_deg_measured` is the read-back around the gated frames and is what reduction
/// uses. v3 adds the blackbody controller (`blackbody_controller`) and each controlled record's
/// `blackbody_readings`; its `blackbody_temperature_k` is then the mean reading during the frames.
/// v4 adds `ffc_events` (the camera core's flat-field corrections, scheduled or detected) and each
/// record's `audit` (per-frame ids, device and host clocks, FPA; the core's state around the step).
/// v5 adds `camera.microgrid_pattern_deg`: the analyzer angle at each position of a microgrid
/// (division-of-focal-plane) camera's 2×2 cell, or null for a camera without one.
/// v6 adds, per frame of a record's `audit`, the core's frame counter and FFC state when the frames
/// carry the core's telemetry (`device_frame_counter`, `ffc_state`), and `home_checks`: each
/// lost-step check of the stage at its home sensor (when, result, steps since the last good one).
inline constexpr int kSessionSchemaVersion = 6;
/// The oldest version still read.
inline constexpr int kSessionSchemaOldestReadable = 1;
inline constexpr const char* kSessionManifestName = "session.json";

/// The camera as recorded in the manifest (mirrors acquisition::CameraInfo).
struct SessionCamera {
    std::string uri, vendor, model, serial, pixel_format;
    int width = 0, height = 0, bits_per_pixel = 0;
    std::optional<double> frame_rate_hz;
    std::map<std::string, double>
        planck_constants;  ///< FLIR-style R, B, F, O when the camera has them
    /// v5: a microgrid camera's analyzer angles (degrees, [0, 180)) at cell positions (0,0),
    /// (0,1), (1,0), (1,1) of (y mod 2, x mod 2); absent for a plain camera (and in v1–v4).
    std::optional<std::array<double, 4>> microgrid_pattern_deg;
};

/// The rotation stage as recorded in the manifest (mirrors acquisition::StageInfo).
struct SessionStage {
    std::string uri, vendor, model, serial, firmware;
    double counts_per_degree = 0.0;
};

/// What a record holds: polarizer frames of the scene, or reference frames of a blackbody or the
/// shutter.
enum class RecordKind { Polarizer, Blackbody, Shutter };
const char* to_string(RecordKind kind);
/// Parses "polarizer" | "blackbody" | "shutter"; std::nullopt otherwise.
std::optional<RecordKind> record_kind_from_string(const std::string& text);

/// When a step happened and which frames it kept (schema v2). All instants are host CLOCK_REALTIME
/// in ns since the Unix epoch, the clock of the frames' reception timestamps
/// (docs/acquisition-cameras.md, "Timing model"). A frame was kept only if reception −
/// exposure_window_ns ≥ settle_end_ns.
struct StepTiming {
    std::int64_t move_start_ns = 0;  ///< the move command was sent
    std::int64_t move_end_ns = 0;    ///< the stage reported the move complete
    std::int64_t settle_end_ns = 0;  ///< move end + settle_s: frames must be exposed after this
    std::int64_t exposure_window_ns =
        0;  ///< subtracted from a frame's reception time to bound its exposure start
    double angle_deg_before_frames =
        0.0;  ///< stage read-back after settling, before the first kept frame
    double angle_deg_after_frames = 0.0;  ///< stage read-back after the last kept frame
    std::int64_t stale_frames_discarded =
        0;  ///< frames exposed (partly) before settle_end_ns, thrown away

    bool operator==(const StepTiming&) const = default;
};

/// What a blackbody controller read while a record's frames were taken (schema v3; absent for a
/// blackbody placed by hand). Temperatures are the control sensor's, kelvin.
struct BlackbodyReadings {
    double set_point_k = 0.0;
    double mean_k = 0.0;  ///< mean of the readings (the record's blackbody_temperature_k)
    double std_k = 0.0;   ///< their sample standard deviation (0 for one reading)
    double min_k = 0.0, max_k = 0.0;
    std::int64_t readings = 0;  ///< polls during the frames, ≥ 1
    bool stable = false;        ///< the controller's stability flag was set at every poll
    double wait_s =
        0.0;  ///< from the set-point command until it was stable within tolerance long enough

    bool operator==(const BlackbodyReadings&) const = default;
};

/// What the camera said about each kept frame of a record, and the camera core's state around the
/// step when a control link reports it (schema v4, written by the capture loop). In the manifest
/// only: a record adopted on resume from its EXR header has none. Per-frame vectors hold one entry
/// per kept frame, in order (as many as the record's `frames`).
struct FrameAudit {
    std::vector<std::int64_t> frame_id;             ///< the device's frame ids, unwrapped
    std::vector<std::int64_t> device_timestamp_ns;  ///< the device's clock (0 when it has none)
    std::vector<std::int64_t> host_timestamp_ns;    ///< host CLOCK_REALTIME at reception
    std::vector<std::optional<double>> fpa_temperature_k;  ///< per frame when the camera reports it
    /// v6, per frame, from telemetry the core wrote into the frame (a Lepton's rows): the core's
    /// own frame counter and its FFC state (0 never commanded, 1 imminent, 2 in progress, 3
    /// complete). Both empty when no frame of the record carried telemetry.
    std::vector<std::optional<std::int64_t>> device_frame_counter;
    std::vector<std::optional<int>> ffc_state;
    std::int64_t incomplete = 0;  ///< frames the camera discarded as damaged during the step
    /// The core's state from its control link (absent without one), read before and after the
    /// frames.
    struct CoreState {
        std::string ffc_mode, gain_mode;  ///< "manual", "auto", ...; "high", "low", ...
        double fpa_temperature_k = 0.0;
        std::int64_t device_frame_count = 0;
        std::int64_t last_ffc_frame_count = 0;
        bool operator==(const CoreState&) const = default;
    };
    std::optional<CoreState> core_before, core_after;

    bool operator==(const FrameAudit&) const = default;
};

/// The blackbody controller as recorded in the manifest (mirrors acquisition::BlackbodyInfo).
struct SessionBlackbodyController {
    std::string uri, vendor, model, serial, firmware;

    bool operator==(const SessionBlackbodyController&) const = default;
};

/// A flat-field correction (FFC) of the camera core during the capture (schema v4). An FFC shifts
/// every pixel's offset, so the polarizer cycle it falls in is biased; the capture schedules FFCs
/// between cycles and repeats a cycle an FFC was detected in (docs/acquisition-cameras.md, "FLIR
/// Boson").
struct FfcEvent {
    enum class Kind {
        Scheduled,  ///< commanded by the capture between polarizer cycles
        Detected,   ///< found in a cycle (control link or frame data); that cycle was taken again
    };
    Kind kind = Kind::Scheduled;
    std::int64_t host_timestamp_ns = 0;  ///< host CLOCK_REALTIME when it was commanded or detected
    int repeat = 0;  ///< the polarizer cycle (plan repeat) it preceded or fell in
    std::optional<double> fpa_temperature_k;  ///< the core's FPA temperature then, when known
    std::optional<std::int64_t>
        device_frame_count;  ///< the core's frame counter at the FFC, when known
    std::string reason;  ///< why: "every cycle", "FPA moved 0.62 K", "frame mean stepped by 23.4
                         ///< counts", ...

    bool operator==(const FfcEvent&) const = default;
};
const char* to_string(FfcEvent::Kind kind);  ///< "scheduled", "detected"

/// A lost-step check of the rotation stage (schema v6): the capture turned to counted 0°, where the
/// home sensor must be active; a stage whose read-back is its step counter cannot see lost steps
/// otherwise (docs/acquisition-stages.md, "Unkind stages"). When it fails, the angles of the steps
/// since the last passing check are uncertain.
struct HomeCheck {
    std::int64_t host_timestamp_ns = 0;  ///< host CLOCK_REALTIME when the sensor was read
    bool passed = false;                 ///< the home sensor was active at counted 0°
    int before_step = 0;  ///< plan index (0-based) of the step it preceded; the plan's step count
                          ///< for the check after the last step
    /// Steps taken since the last passing check of this run (or since its first step).
    std::int64_t steps_since_last_good = 0;

    bool operator==(const HomeCheck&) const = default;
};

/// One recorded step: N frames averaged into one EXR.
struct SessionRecord {
    RecordKind kind = RecordKind::Polarizer;
    std::string file;                  ///< relative to the session dir: "frames/<name>.exr"
    double angle_deg_requested = 0.0;  ///< polarizer angle asked of the stage, degrees [0, 360)
    double angle_deg_measured = 0.0;   ///< angle read back from the stage after settling, degrees
    int repeat = 0;                    ///< 0-based repeat index within the plan
    std::optional<double>
        blackbody_temperature_k;  ///< set for blackbody (required) and shutter (optional)
    std::int64_t frames = 0;      ///< frames averaged
    std::int64_t dropped = 0;     ///< frames the camera dropped while these were grabbed
    std::int64_t first_timestamp_ns =
        0;  ///< host CLOCK_REALTIME of the first frame, ns since the epoch
    std::int64_t last_timestamp_ns = 0;  ///< ... of the last frame
    std::optional<double>
        fpa_temperature_k;             ///< mean sensor temperature when the camera reports it
    std::optional<StepTiming> timing;  ///< v2 records written by the capture loop; absent in v1
    std::optional<BlackbodyReadings> blackbody_readings;  ///< v3: set by a blackbody controller
    std::optional<FrameAudit> audit;  ///< v4: per-frame ids, clocks and FPA; the core's state

    bool operator==(const SessionRecord&) const = default;
};

/// The whole manifest.
struct SessionManifest {
    int schema_version =
        kSessionSchemaVersion;  ///< as read (1 to 6); always written as kSessionSchemaVersion
    std::string created_utc;    ///< ISO 8601, e.g. "2026-11-22T16:19:20Z"
    SessionCamera camera;
    SessionStage stage;
    std::optional<SessionBlackbodyController>
        blackbody_controller;                        ///< v3: when a controller set the blackbody
    nlohmann::json plan = nlohmann::json::object();  ///< the capture plan as run
    nlohmann::json metadata =
        nlohmann::json::object();  ///< free form (site, operator, targets, ...)
    std::vector<SessionRecord> records;
    std::vector<FfcEvent> ffc_events;    ///< v4; empty when the camera core reports none
    std::vector<HomeCheck> home_checks;  ///< v6; empty without plan home_check_every
    bool complete = false;
};

/// The polarizer angle a record's frames were taken at: `angle_deg_measured` from schema v2 on
/// (read back around the gated frames), `angle_deg_requested` for v1 sessions, whose read-back
/// preceded frames that may have been exposed during the move.
double record_polarizer_angle_deg(const SessionManifest& manifest, const SessionRecord& record);

/// Manifest ⇄ JSON (schema v6; v1 to v5 read). `from_json` validates everything and throws
/// tirpol::Error naming `source` (the file) and the field, e.g. "DIR/session.json:
/// records[2].frames: expected an integer ≥ 1".
nlohmann::json session_to_json(const SessionManifest& manifest);
SessionManifest session_from_json(const nlohmann::json& json, const std::string& source);

/// Writes the record's fields into EXR header attributes (and reads them back); the EXR then
/// describes itself. 64-bit timestamps are stored as decimal strings (an EXR int is 32-bit).
void record_to_attributes(const SessionRecord& record, Attributes& attributes);
SessionRecord record_from_attributes(const Attributes& attributes, const std::string& file,
                                     const std::string& source);

/// Reads and validates `dir/session.json`: schema name and version, every field's type and range,
/// every record's frame file present, no file listed twice. Throws tirpol::Error otherwise.
SessionManifest read_session(const std::filesystem::path& dir);

/// Reads one record's EXR and checks it has `counts` and `counts_std` at the camera's size, and
/// that what its header says of itself (kind, angle_deg_requested, angle_deg_measured,
/// blackbody_temperature_k, camera_serial, camera_model; SessionWriter::add_record writes them)
/// agrees with the manifest's record and camera: tirpol::Error naming the frame, the manifest, the
/// field and both values otherwise (a frame at 90° filed under 0° would be reduced with S1
/// negated).
Image read_session_frame(const std::filesystem::path& dir, const SessionManifest& manifest,
                         const SessionRecord& record);

/// The "frames/<stem>.exr" name for a record; `stem` may use [A-Za-z0-9._+-] only.
std::string session_frame_file(const std::string& stem);

/// Appends to a session directory. Holds an exclusive lock on the directory while open, so two
/// processes never write the same session.
class SessionWriter {
public:
    /// Starts a new session in `dir`. Refuses a directory that exists and is not empty (use
    /// resume()). Atomic: the directory, `frames/`, the lock and the manifest with no records are
    /// built in a hidden sibling (`.<name>.creating-*`) and renamed to `dir` in one step, so a
    /// crash or a full disk leaves either nothing or a complete empty session.
    static SessionWriter create(const std::filesystem::path& dir, SessionManifest manifest);
    /// Reopens an interrupted session: reads and validates the manifest, deletes leftover temporary
    /// files (`.session.json.tmp-*`, hidden files in `frames/`), and adopts frame files that were
    /// written but not yet listed (crash between the two writes), using the record their header
    /// carries. Refuses a v1 session (finish it with the tirpol that started it, or start anew).
    static SessionWriter resume(const std::filesystem::path& dir);

    SessionWriter(SessionWriter&&) noexcept;
    SessionWriter& operator=(SessionWriter&&) noexcept;
    ~SessionWriter();

    const SessionManifest& manifest() const { return m_manifest; }
    const std::filesystem::path& dir() const { return m_dir; }
    /// Whether a record with this file ("frames/<stem>.exr") is already in the session.
    bool has_record(const std::string& file) const;
    /// Frame files recovered by resume() (empty after create()).
    const std::vector<std::string>& adopted_files() const { return m_adopted; }

    /// Writes `frame` (channels `counts` and `counts_std`, camera-sized) to record.file with the
    /// record mirrored into its header, then rewrites the manifest. Throws tirpol::Error if the
    /// file is already recorded or exists on disk (never overwrites), or if the session is
    /// complete.
    void add_record(const SessionRecord& record, const Image& frame);
    /// Sets the frame rate the camera delivered (measured, Hz); written with the next manifest
    /// write (add_record, mark_complete).
    void set_camera_frame_rate(double frame_rate_hz);
    /// Appends a flat-field correction event and rewrites the manifest.
    void add_ffc_event(const FfcEvent& event);
    /// Appends a lost-step check of the stage and rewrites the manifest.
    void add_home_check(const HomeCheck& check);
    /// Replaces the free-form metadata and rewrites the manifest.
    void set_metadata(nlohmann::json metadata);
    /// Marks the session complete and rewrites the manifest.
    void mark_complete();

private:
    struct Lock;
    SessionWriter(std::filesystem::path dir, SessionManifest manifest, std::unique_ptr<Lock> lock);
    void write_manifest() const;

    std::filesystem::path m_dir;
    SessionManifest m_manifest;
    std::unique_ptr<Lock> m_lock;
    std::vector<std::string> m_adopted;
};

}  // namespace tirpol
