#pragma once
/// \file lepton_control.h
/// A FLIR Lepton on a PureThermal board: its CCI through UVC extension units (lepton_cci.h), as an
/// FfcControl for the capture's FFC scheduling and detection (ffc.h). The kernel's seam is
/// LeptonXu: on Linux the V4L2 device's UVCIOC_CTRL_QUERY ioctl (open_v4l2_lepton_xu); in tests a
/// simulated Lepton answering at that seam. The FFC marker and the frame counter come from the
/// telemetry row that the board appends to each Y16 frame when telemetry is enabled
/// (observe_telemetry): the CCI has no frame counter.

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/internal/lepton_cci.h"
#include "tirpol/acquisition/internal/lepton_frame.h"

namespace tirpol::acquisition {

/// UVC extension-unit controls: GET_CUR and SET_CUR of one control of one unit.
class LeptonXu {
public:
    virtual ~LeptonXu() = default;
    /// Reads the control's current value into `data` (its whole length).
    virtual Status get(std::uint8_t unit, std::uint8_t selector, std::span<std::uint8_t> data) = 0;
    virtual Status set(std::uint8_t unit, std::uint8_t selector,
                       std::span<const std::uint8_t> data) = 0;
    /// For messages: "/dev/video0".
    virtual std::string name() const = 0;
};

/// The extension units of a V4L2 (uvcvideo) device, through UVCIOC_CTRL_QUERY. A path that does not
/// open is a DeviceError naming it.
Result<std::unique_ptr<LeptonXu>> open_v4l2_lepton_xu(const std::string& device_path);

struct LeptonControlOptions {
    std::chrono::milliseconds ffc_timeout{3000};  ///< an FFC takes about 0.5 s (shutter closed)
    std::chrono::milliseconds ffc_poll{20};
};

/// TLinear: radiometric output in kelvin × 10 (0.1 K) or × 100 (0.01 K) per count.
enum class LeptonTLinearResolution { TenthKelvin = 0, HundredthKelvin = 1 };

class LeptonControl final : public FfcControl {
public:
    LeptonControl(std::unique_ptr<LeptonXu> xu, LeptonControlOptions options = {});

    // CCI commands (IDD 110-0144) through the extension units.
    Result<std::vector<std::uint16_t>> get(std::uint16_t command_id, std::size_t words);
    Status set(std::uint16_t command_id, std::span<const std::uint16_t> words);
    Status run(std::uint16_t command_id);

    /// RAD TLinear enable and resolution: the Y16 counts become scene temperature.
    Status set_tlinear(bool enabled, LeptonTLinearResolution resolution);
    Result<bool> tlinear_enabled();
    Result<LeptonTLinearResolution> tlinear_resolution();
    /// SYS FFC shutter mode, changing only the mode in the core's object.
    Status set_ffc_mode(lepton::FfcShutterMode::Mode mode);
    Result<lepton::FfcShutterMode> ffc_shutter_mode();
    /// SYS telemetry enable (the board then appends the telemetry rows to each frame).
    Status set_telemetry(bool enabled);
    /// SYS telemetry location: where in the frame the rows go (lepton_frame.h).
    Status set_telemetry_location(LeptonTelemetryLocation location);

    /// Feeds the telemetry row of a frame as it arrives; thread-safe.
    void observe_telemetry(const lepton::Telemetry& telemetry);
    /// Frames since the last FFC, from the telemetry seen (InvalidArgument-free: NotSupported
    /// until a telemetry row has been observed since an FFC).
    Result<std::uint64_t> frames_since_ffc();

    // FfcControl
    Status set_manual_ffc() override;
    Status run_ffc_and_wait() override;
    Result<double> fpa_temperature_k() override;
    /// The telemetry frame counter at the last FFC seen.
    Result<std::uint64_t> last_ffc_marker() override;
    Result<std::uint64_t> device_frame_count() override;
    Result<FrameAudit::CoreState> core_state() override;
    /// A frame's telemetry (Frame::telemetry, split off by the Lepton camera) goes to
    /// observe_telemetry; a frame without it is ignored.
    void observe_frame(const Frame& frame) override;
    void set_frame_pull(std::function<void()> pull) override;

private:
    Result<lepton::Telemetry> latest_telemetry();
    /// Waits one poll interval: pulls a frame when the capture lent a way to, else sleeps.
    void wait_a_little();

    std::unique_ptr<LeptonXu> m_xu;
    LeptonControlOptions m_options;
    std::mutex m_mutex;  // the telemetry fields below
    std::optional<lepton::Telemetry> m_latest;
    std::optional<std::uint32_t> m_frame_at_last_ffc;
    std::function<void()> m_pull;  // set and used on the capturing thread only
};

/// A LeptonControl over `xu` after checking that a Lepton answers (its FFC shutter mode object
/// reads back) and switching its telemetry on at the footer, where the PureThermal firmware puts
/// it: the capture's FFC marker and frame counter come from those rows
/// (`v4l2:///dev/videoN?format=Y16&width=160&height=122&telemetry=footer` splits them off). A core
/// that does not answer is a DeviceError naming the device.
Result<std::unique_ptr<LeptonControl>> open_lepton_control(std::unique_ptr<LeptonXu> xu,
                                                           LeptonControlOptions options = {});

}  // namespace tirpol::acquisition
