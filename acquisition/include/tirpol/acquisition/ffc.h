#pragma once
/// \file ffc.h
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

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "tirpol/acquisition/camera.h"
#include "tirpol/acquisition/result.h"
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

}  // namespace tirpol::acquisition
