#pragma once
/// \file boson_control.h
/// The FLIR Boson's control link: FSLP commands (boson_fslp.h) over its USB CDC-ACM serial port
/// (/dev/ttyACM0, 921600 8N1 as flirpy opens it; a pseudo-terminal for the simulator). One command
/// at a time, each waited for: a reply is matched by its sequence number and function code. Every
/// failure is a value naming the port, the function and what came back:
/// - Timeout: no reply to the command within reply_timeout (the core stopped answering);
/// - BadReply: a frame with a bad CRC or escape, a reply carrying another sequence number than the
///   command's (a late reply to an earlier command is skipped, anything else is an error), another
///   function code, or fewer data bytes than the function returns;
/// - DeviceFault: the reply's FLR_RESULT status is not R_SUCCESS (named, e.g.
/// R_CAM_API_INVALID_INPUT). Function codes and data layouts: boson_fslp.h, which cites the SDK
/// headers and flirpy.

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/internal/boson_fslp.h"
#include "tirpol/acquisition/internal/byte_port.h"

namespace tirpol::acquisition {

struct BosonControlOptions {
    std::chrono::milliseconds reply_timeout{500};  ///< per command; the core answers in a few ms
    std::chrono::milliseconds ffc_timeout{
        5000};                               ///< run_ffc_and_wait: the shutter FFC takes ~0.5 s
    std::chrono::milliseconds ffc_poll{20};  ///< FFC status polling period while waiting
};

/// The FFC bookkeeping the core keeps, read in one go.
struct BosonFfcState {
    boson::FfcStatus status = boson::FfcStatus::NoFfcPerformed;
    bool in_progress = false;
    std::uint32_t frame_count = 0;           ///< ROIC frames since power-up
    std::uint32_t last_ffc_frame_count = 0;  ///< frame count when the last FFC ran (0: none yet)
};

/// Also the capture's FfcControl (ffc.h): manual mode, FFC and wait, FPA, last-FFC frame count.
class BosonControl final : public FfcControl {
public:
    /// Takes the port; `name` ("boson:///dev/ttyACM0") prefixes messages.
    BosonControl(std::unique_ptr<BytePort> port, std::string name,
                 BosonControlOptions options = {});

    const std::string& name() const { return m_name; }
    Result<std::uint32_t> camera_serial();
    /// The part number, trailing NULs and spaces removed ("20640A050-6IAAX").
    Result<std::string> part_number();
    /// BOSON_LOOKUPFPATEMPDEGCX10 converted to kelvin.
    Result<double> fpa_temperature_k() override;
    Result<boson::FfcMode> ffc_mode();
    Status set_ffc_mode(boson::FfcMode mode);
    /// Starts an FFC; returns when the core acknowledged (the FFC itself runs on, ~0.5 s).
    Status run_ffc();
    /// Runs an FFC and polls until the core reports it complete and no longer in progress.
    Status run_ffc_and_wait() override;
    Result<boson::FfcStatus> ffc_status();
    Result<bool> ffc_in_progress();
    Result<std::uint32_t> last_ffc_frame_count();
    Result<std::uint32_t> frame_count();
    Result<BosonFfcState> ffc_state();
    Result<boson::GainMode> gain_mode();
    Status set_gain_mode(boson::GainMode mode);
    /// FPA change in kelvin that makes the core run an auto FFC.
    Result<double> ffc_temperature_threshold_k();
    Status set_ffc_temperature_threshold_k(double threshold_k);

    Status set_manual_ffc() override { return set_ffc_mode(boson::FfcMode::Manual); }
    Result<std::uint64_t> last_ffc_marker() override;
    Result<std::uint64_t> device_frame_count() override;
    Result<FrameAudit::CoreState> core_state() override;

    /// Sends one command and returns its reply's data (at least `reply_bytes` long).
    Result<std::vector<std::uint8_t>> transact(std::uint32_t function,
                                               std::vector<std::uint8_t> data,
                                               std::size_t reply_bytes);

private:
    Result<std::int32_t> get_i32(std::uint32_t function);
    Result<std::uint32_t> get_u32(std::uint32_t function);
    Result<std::int16_t> get_i16(std::uint32_t function);
    Status set_i32(std::uint32_t function, std::int32_t value);

    std::unique_ptr<BytePort> m_port;
    std::string m_name;
    BosonControlOptions m_options;
    std::uint32_t m_sequence = 0;
    boson::FrameDecoder m_decoder;
};

/// Opens a Boson's control port (921600 8N1) and checks a Boson answers: reads its serial and part
/// numbers. `uri` names it in messages.
Result<std::unique_ptr<BosonControl>> open_boson_control(const std::string& port_path,
                                                         const std::string& uri,
                                                         BosonControlOptions options = {});

}  // namespace tirpol::acquisition
