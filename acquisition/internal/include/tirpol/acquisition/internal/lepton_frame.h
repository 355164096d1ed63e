#pragma once
/// \file lepton_frame.h
/// A FLIR Lepton's telemetry rows inside a PureThermal Y16 frame, and the camera that splits them
/// off. With telemetry enabled the Lepton sends three extra VoSPI packets of 80 words per frame
/// (telemetry rows A, B and C; Lepton IDD 110-0144, "Telemetry"); a Lepton 3.x sends one extra
/// packet per segment, four in all, the fourth reserved. The PureThermal firmware puts them at the
/// footer (it commands LEP_TELEMETRY_LOCATION_FOOTER) and hands the whole image to UVC, so a frame
/// is 80×63 (Lepton 2.x: rows 60–62 are A, B, C) or 160×122 (Lepton 3.x: row 120 is A|B, row 121
/// C|reserved); in header location the same rows come first. Y16 words are little-endian and the
/// V4L2 back end converts them to float exactly, so the telemetry words are recovered bit for bit.

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tirpol/acquisition/camera.h"
#include "tirpol/acquisition/internal/lepton_cci.h"

namespace tirpol::acquisition {

/// Where the Lepton puts its telemetry rows (LEP_SYS_TELEMETRY_LOCATION).
enum class LeptonTelemetryLocation { Header, Footer };

/// A PureThermal frame with telemetry: the image inside it and the telemetry rows around it.
struct LeptonFrameLayout {
    int image_width = 0, image_height = 0;
    int telemetry_rows = 0;  ///< 3 (Lepton 2.x, 80 words each) or 2 (Lepton 3.x, 160 words each)
};

/// The layout of a frame of this size: 80×63 (Lepton 2.x) or 160×122 (Lepton 3.x); std::nullopt
/// for any other size (a frame without telemetry, or not a Lepton's).
std::optional<LeptonFrameLayout> lepton_telemetry_layout(int width, int height);

/// Splits a frame of a layout above: returns the telemetry words (row A first, then B, C and, for
/// a Lepton 3.x, the reserved packet) and shrinks `frame` to the image. std::nullopt, with `frame`
/// untouched, when the frame's size has no such layout.
std::optional<std::vector<std::uint16_t>> split_lepton_telemetry(Frame& frame,
                                                                 LeptonTelemetryLocation location);

/// The frame's fields from telemetry row A: `fpa_temperature_k` and `telemetry`.
void apply_lepton_telemetry(const lepton::Telemetry& telemetry, Frame& frame);

/// A Lepton's camera (PureThermal's UVC video:
/// `v4l2:///dev/videoN?format=Y16&width=160&height=122&telemetry=footer`) whose frames carry
/// telemetry rows: each grabbed frame has them split off (so the image is 80×60 or 160×120 and
/// `info()` says so) and row A decoded into the frame (`Frame::telemetry`,
/// `Frame::fpa_temperature_k`). Opening fails with NotSupported when the inner camera's size has no
/// telemetry layout (telemetry not enabled on the core, or not a Lepton); a frame whose row A does
/// not parse (revision word 0: telemetry switched off mid-stream, or at the other end of the frame)
/// is a BadReply naming the frame.
Result<std::unique_ptr<Camera>> wrap_lepton_telemetry_camera(std::unique_ptr<Camera> inner,
                                                             LeptonTelemetryLocation location);

}  // namespace tirpol::acquisition
