#pragma once
/// \file display_frame.h
/// What the page draws: camera counts turned into the display quantity (counts, or with a
/// radiometric calibration apparent radiance or brightness temperature, through calibration's own
/// counts_to_radiance / brightness_temperature), with saturated and dead pixels flagged, and the
/// compact binary the page receives.
///
/// Wire format (little-endian), one message = one image set:
///   "TPLV" | u32 header_bytes | header JSON (UTF-8, padded with spaces to an even length) |
///   per channel: width × height u16 codes
/// Codes: 0 = no value (NaN), 1 = dead pixel, 65535 = saturated, 2…65534 = linear from the
/// channel's `min` to `max` (value = min + (code − 2)·(max − min)/65532): a 16-bit step is below
/// the NETD of any 14-bit camera, and a 640×512 frame is 640 KiB instead of 1.25 MiB of float.

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/acquisition/camera.h"
#include "tirpol/calibration/radiometric.h"
#include "tirpol/live/live_server.h"

namespace tirpol::live {

/// Per-pixel flags.
enum PixelFlag : std::uint8_t { kPixelOk = 0, kPixelSaturated = 1, kPixelDead = 2 };

struct DisplayChannel {
    std::string name;   ///< "S0", "S1", "DoLP", ...
    std::string units;  ///< "counts", "W/(m²·sr)", "K", "", "deg"
    std::vector<float> values;
    std::vector<std::uint8_t> flags;  ///< PixelFlag per pixel; empty = all ok
};

struct DisplayImage {
    int width = 0, height = 0;
    std::vector<DisplayChannel> channels;
    nlohmann::json info =
        nlohmann::json::object();  ///< copied into the header (frame id, angles, ...)
};

class DisplayConverter {
public:
    /// `calibration` (may be null: counts only) must outlive the converter; Radiance and
    /// Temperature need it (tirpol::Error otherwise, or when its size differs from the camera's).
    DisplayConverter(const acquisition::CameraInfo& camera,
                     const calibration::RadiometricCalibration* calibration, DisplayUnit unit);

    DisplayUnit unit() const { return m_unit; }
    /// Units of converted values ("counts", "W/(m²·sr)", "K").
    std::string units() const;
    /// The counts level at and above which a pixel is saturated (2^bits − 1), if the format has
    /// one.
    std::optional<double> saturation_counts() const { return m_saturation_counts; }

    /// Counts → display quantity, NaN where it has no value. Throws tirpol::Error when an
    /// FPA-dependent calibration meets a frame without FPA temperature.
    std::vector<float> convert(const std::vector<float>& counts,
                               std::optional<double> fpa_temperature_k) const;
    /// Counts → radiance (or the counts themselves without a calibration): the signal the Stokes
    /// reduction takes, so that S0 is in radiance when a calibration is given.
    std::vector<float> to_signal(const std::vector<float>& counts,
                                 std::optional<double> fpa_temperature_k) const;
    /// Saturated (counts ≥ saturation level) and dead pixels (the calibration's bad-pixel map;
    /// without one, pixels reading 0 counts: a dead readout channel).
    std::vector<std::uint8_t> flags(const std::vector<float>& counts) const;
    /// The live S0 image of one frame: channel "S0" and info {frame_id, fpa_temperature_k}.
    DisplayImage frame_image(const acquisition::Frame& frame) const;

private:
    const calibration::RadiometricCalibration* m_calibration;
    DisplayUnit m_unit;
    int m_width, m_height;
    std::optional<double> m_saturation_counts;
};

/// The wire format above. Channel value ranges are the finite min/max of the unflagged pixels.
std::string encode_display_image(const DisplayImage& image);

}  // namespace tirpol::live
