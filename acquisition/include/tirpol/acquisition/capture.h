#pragma once
/// \file capture.h
/// The capture loop: for each plan step not yet in the session — move the stage, settle, read the
/// angle back and check it, discard every frame exposed before the settle end (FrameGate: a
/// free-running camera's queue holds frames from the move), keep the next N, read the angle back
/// again (a stage that moved during the frames fails the step), average the frames (mean and
/// standard deviation per pixel), and hand the record to a writer thread so that EXR writing never
/// stalls grabbing. Software trigger is not needed. Device failures become tirpol::Error naming the
/// step; everything recorded before stays, and running again on the resumed session continues with
/// the first missing step.
///
/// Flat-field corrections (FFC) and the polarizer cycle. An uncooled core (FLIR Boson, Lepton)
/// closes a shutter now and then and re-measures every pixel's offset; the image level steps. A
/// step inside a 0/45/90/135 cycle lands in S1 and S2 (S1 = I0 − I90 takes the step whole when it
/// falls between the 0° and 90° frames). The capture therefore (CaptureOptions::ffc):
/// - with a control link (FfcControl): puts the core in manual FFC mode and runs an FFC between
///   cycles, by the schedule below; a cycle in which the core still ran one (its last-FFC frame
///   count moved) is taken again;
/// - without a link: watches the frames for an offset step (a frame mean jumping within a
///   step; for a 0/45/90/135 plan the cycle closure I0 + I90 − I45 − I135, zero for any linear
///   analyzer; the change of each angle's mean from the last accepted cycle, equal for all angles
///   when the scene holds still) and takes the cycle again when it finds one.
/// Every FFC commanded or detected goes into the session (SessionManifest::ffc_events).
///
/// Opening the session a capture plan writes into, shared by `tirpol acquire` and the live view's
/// capture button: a new session for these devices and this plan, or an interrupted one resumed
/// after checking it was started with the same plan and camera format; and the whole of `tirpol
/// acquire` (devices by URI, the plan file, Ctrl-C) as one call.
///
/// What Ctrl-C (SIGINT/SIGTERM) does during `tirpol acquire`: a signal handler can only set a flag,
/// and the capture loop may be blocked in a move, a homing or a device call. A watcher thread turns
/// the flag into Stage::stop() (repeated every `restop_period`, so a move that starts just after
/// the first stop is stopped too) and, if the program has still not finished `grace` after the
/// signal, calls `on_overdue` (the CLI prints where the session is and exits: every session write
/// is atomic, so nothing recorded is lost).

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/acquisition/blackbody.h"
#include "tirpol/acquisition/camera.h"
#include "tirpol/acquisition/capture_plan.h"
#include "tirpol/acquisition/result.h"
#include "tirpol/acquisition/stage.h"
#include "tirpol/core/interrupt_signals.h"
#include "tirpol/core/session.h"

namespace tirpol::acquisition {

/// A camera core whose FFC the capture can command (a FLIR Boson or Lepton over its control link).
class FfcControl {
public:
    virtual ~FfcControl() = default;
    /// Stops the core from correcting on its own (Boson: BOSON_SETFFCMODE manual).
    virtual Status set_manual_ffc() = 0;
    /// Runs an FFC and returns once the core reports it complete.
    virtual Status run_ffc_and_wait() = 0;
    virtual Result<double> fpa_temperature_k() = 0;
    /// A count that changes whenever the core has run an FFC (Boson: the frame count at the last
    /// FFC).
    virtual Result<std::uint64_t> last_ffc_marker() = 0;
    /// The core's own frame counter now.
    virtual Result<std::uint64_t> device_frame_count() = 0;
    /// FFC and gain modes, FPA temperature, frame count and last-FFC frame count in one go: the
    /// capture records it before and after each step's frames (SessionRecord::audit).
    virtual Result<FrameAudit::CoreState> core_state() = 0;
    /// Each frame the capture grabs, for a core that reports its state inside the frames (a
    /// Lepton's telemetry rows: Frame::telemetry); the default ignores them.
    virtual void observe_frame(const Frame& frame) { (void)frame; }
    /// While it runs, the capture lends the link a way to grab the next frame (and pass it to
    /// observe_frame): a link whose core reports only through the frames pulls them while it waits
    /// for an FFC to show. Empty: no frames to pull (the link then waits on its own clock). The
    /// default ignores it.
    virtual void set_frame_pull(std::function<void()> pull) { (void)pull; }
};

struct FfcOptions {
    /// Null: no link; FFCs are only detected in the frames.
    FfcControl* control = nullptr;
    enum class Schedule {
        EveryCycle,  ///< an FFC before every polarizer cycle
        EveryN,      ///< before every `every_n_cycles`-th cycle (the first included)
        FpaDelta,  ///< before a cycle when the FPA moved by more than `fpa_delta_k` since the last
                   ///< FFC
    };
    Schedule schedule = Schedule::EveryCycle;
    int every_n_cycles = 1;
    double fpa_delta_k = 0.5;
    /// Without a link: a kept frame whose mean differs from its step's mean so far by more than
    /// this is an offset step.
    double frame_step_counts = 5.0;
    /// Without a link: |I0 + I90 − I45 − I135| of the step means, and the spread of the per-angle
    /// change from the last accepted cycle, above this are an offset step in the cycle.
    double cycle_step_counts = 5.0;
    /// Attempts of one cycle before the capture gives up (an FFC every cycle means a core out of
    /// control).
    int max_cycle_attempts = 4;
    /// Without a link: wait this long after a detection before taking the cycle again (the shutter
    /// of a Boson FFC stays closed about 0.5 s).
    double detection_pause_s = 1.0;
};

/// Opens a core's control link by URI: `boson:///dev/ttyACM0[?timeout_ms=500]` (a Boson's CDC-ACM
/// port, or the simulator's pty) or `lepton:///dev/video0[?ffc_timeout_ms=3000]` (a Lepton on a
/// PureThermal board: its UVC extension units; telemetry switched on at the footer). Bad URI:
/// tirpol::Error naming it; an absent device or a core that does not answer: a DeviceError.
Result<std::unique_ptr<FfcControl>> open_ffc_control(const std::string& uri);

/// Parses `tirpol acquire --ffc`: "detect" (no link: watch the frames only), "every-cycle",
/// "every:N" (N ≥ 1 cycles) or "fpa:K" (K > 0 kelvin). Throws tirpol::Error naming the text and the
/// choices.
FfcOptions parse_ffc_schedule(const std::string& text);

/// Where a capture stands, for CaptureOptions::on_progress.
struct CaptureProgress {
    enum class Event {
        Frame,         ///< a frame was kept for the current step (exposed after its settle end)
        StepRecorded,  ///< the step's averaged record was handed to the session writer
    };
    Event event = Event::Frame;
    /// The current step (index, kind, label, angle_deg, file); never null, valid during the call.
    const CaptureStep* step = nullptr;
    std::size_t steps_total = 0;  ///< steps in the plan
    std::size_t steps_recorded =
        0;  ///< steps in the session, earlier runs included (this one counted once recorded)
    int frames_kept = 0;         ///< frames of the current step averaged so far (of step->frames)
    std::uint64_t frame_id = 0;  ///< Frame: the id of the frame just kept
};

struct CaptureOptions {
    /// Called before each reference step with an instruction for the operator ("Put the blackbody
    /// at 313.15 K in front of the camera"); return false to stop. Empty = non-interactive.
    std::function<bool(const std::string& instruction)> prompt;
    /// Progress bar stream (nullptr: none).
    std::FILE* progress_stream = stderr;
    /// Set (e.g. by a SIGINT handler) to stop after the current frame; the session stays resumable.
    const std::atomic<bool>* interrupt = nullptr;
    /// Sets the temperatures of the plan's controlled blackbody references (required when the plan
    /// has any: capture_plan.h `controller`); each such step first waits for the set-point
    /// (blackbody_wait.h), polls the controller during its frames and records the readings.
    BlackbodyController* blackbody = nullptr;
    /// Called on the capturing thread after each kept frame and after each recorded step (a
    /// notebook's progress bar). An exception it throws ends the capture like a device error: the
    /// steps recorded before stay and the session resumes. Empty: not called.
    std::function<void(const CaptureProgress&)> on_progress;
    /// Flat-field corrections (ffc.h): set, the polarizer steps of each plan repeat are one cycle
    /// whose records are written only once the cycle is free of FFCs; FFCs are scheduled between
    /// cycles through `ffc->control` when given, and a cycle an FFC fell in is taken again. Null:
    /// frames are not watched for FFCs (a core left in auto FFC can bias S1 and S2).
    const FfcOptions* ffc = nullptr;
};

struct CaptureSummary {
    std::size_t steps_total = 0;
    std::size_t steps_already_recorded = 0;  ///< found in the session when the run started
    std::size_t steps_recorded = 0;          ///< recorded by this run
    std::uint64_t frames = 0, dropped = 0;   ///< by this run
    std::uint64_t stale_discarded =
        0;  ///< frames exposed before their step's settle end, by this run
    std::optional<double> delivered_frame_rate_hz;  ///< measured from the frames' reception times
    int ffc_scheduled = 0;  ///< FFCs run between cycles by this run (CaptureOptions::ffc)
    int ffc_detected = 0;   ///< FFCs found inside a cycle, each followed by taking that cycle again
    int home_checks = 0;    ///< passing lost-step checks at the home sensor (plan home_check_every)
};

/// Bytes a session of `steps` records of width × height frames may need (EXR upper bound).
std::uintmax_t session_bytes_needed(int width, int height, std::size_t steps);
/// Throws tirpol::Error saying how much is needed and how much is free when `dir`'s file system
/// cannot hold `steps` more records.
void check_free_space(const std::filesystem::path& dir, int width, int height, std::size_t steps);

/// The manifest of a new session for these devices and this plan (records empty; the camera's
/// frame_rate_hz null until run_capture measures the delivered rate).
SessionManifest new_session_manifest(const CameraInfo& camera, const StageInfo& stage,
                                     const CapturePlan& plan,
                                     const BlackbodyInfo* blackbody = nullptr);

/// Checks that a session being resumed was started with this plan and an identical camera format;
/// throws tirpol::Error naming what differs.
void check_resumable(const SessionManifest& manifest, const CameraInfo& camera,
                     const CapturePlan& plan);

/// Puts a simulated camera (`sim://`, the twin's `sim://<scene.yaml>`) behind the polarizer that
/// `stage` turns, so that each frame shows the scene through the polarizer where the stage has it
/// when the frame is exposed: an in-process `sim://` stage gives its time-true angle (also
/// mid-move); a driver stage (Thorlabs APT, Elliptec — e.g. tirpol-stage-sim on a pseudo-terminal)
/// the last angle its driver moved to or read back (frames taken during a move show the previous
/// angle; the capture's frame gate discards those anyway). A camera that is not simulated, or one
/// given an angle source of its own, is left alone. Returns the stage to use from now on (`stage`
/// itself, or a wrapper that forwards every call to it); the coupling ends when that stage is
/// destroyed.
std::unique_ptr<Stage> couple_simulated_polarizer(Camera& camera, std::unique_ptr<Stage> stage);

/// Runs every step of `plan` that `session` does not have yet, then marks the session complete.
CaptureSummary run_capture(Camera& camera, Stage& stage, const CapturePlan& plan,
                           SessionWriter& session, const CaptureOptions& options = {});

/// `resume` false: SessionWriter::create (refuses a non-empty directory). `resume` true: the
/// directory must hold a session (tirpol::Error "no session to resume here" otherwise), which is
/// reopened with SessionWriter::resume and checked with check_resumable. `blackbody`: the
/// controller of a plan with blackbody set-points (recorded in a new session's manifest).
SessionWriter open_capture_session(const std::filesystem::path& dir, const CameraInfo& camera,
                                   const StageInfo& stage, const CapturePlan& plan, bool resume,
                                   const BlackbodyInfo* blackbody = nullptr);

/// A capture plan run by device URIs into a session directory (`tirpol acquire`).
struct AcquisitionOptions {
    std::filesystem::path plan;  ///< capture plan YAML
    std::filesystem::path session;
    std::string camera_uri, stage_uri;
    std::string blackbody_uri;       ///< empty: no controlled blackbody
    std::string camera_control_uri;  ///< empty: no FFC link (ffc_control.h)
    std::string ffc_schedule;        ///< empty: "every-cycle" with a camera control link, else none
    bool resume = false;             ///< continue the interrupted session in `session`
    /// Asked before reference frames (CaptureOptions::prompt); empty: non-interactive.
    std::function<bool(const std::string& instruction)> prompt;
};

/// What run_acquisition did.
struct AcquisitionResult {
    std::filesystem::path session;
    CaptureSummary summary;
    bool ffc = false;  ///< flat-field corrections were scheduled or watched for
    /// Files found written just before an interruption and adopted by the resumed session.
    std::vector<std::filesystem::path> recovered;
};

/// How long after Ctrl-C run_acquisition may take to leave through its clean path before the
/// process exits anyway (status 1; every session write is atomic, so nothing recorded is lost).
inline constexpr std::chrono::milliseconds kAcquisitionInterruptGrace{1000};

/// Checks the options, opens the devices and the session (new or resumed), and runs the plan.
/// While it runs, the first Ctrl-C (SIGINT/SIGTERM) stops the stage at once, also mid-move or
/// mid-homing, and ends the run after the current frame with a tirpol::Error that says how many
/// steps are recorded; a device that does not return within kAcquisitionInterruptGrace ends the
/// process. Throws tirpol::Error for a bad plan, URI or option combination and device faults.
AcquisitionResult run_acquisition(const AcquisitionOptions& options);

/// The summary `tirpol acquire` prints: steps, frames, dropped frames, flat-field corrections.
std::string acquisition_summary_text(const AcquisitionResult& result);

class StopOnInterrupt {
public:
    StopOnInterrupt(const std::atomic<bool>& interrupt, std::chrono::milliseconds grace,
                    std::function<void()> on_overdue,
                    std::chrono::milliseconds restop_period = std::chrono::milliseconds(250));
    /// Stops watching (joins the thread). Destroy it before the stage it watches.
    ~StopOnInterrupt();
    StopOnInterrupt(const StopOnInterrupt&) = delete;
    StopOnInterrupt& operator=(const StopOnInterrupt&) = delete;

    /// The stage to stop from now on (nullptr: none yet).
    void watch(Stage* stage) { m_stage = stage; }
    /// How many stop commands were sent (for tests and the log).
    int stops_sent() const { return m_stops_sent; }

private:
    bool stop_stage();

    std::atomic<Stage*> m_stage{nullptr};
    std::atomic<int> m_stops_sent{0};
    InterruptWatcher m_watcher;  // last: it stops watching before the members above go
};

}  // namespace tirpol::acquisition
