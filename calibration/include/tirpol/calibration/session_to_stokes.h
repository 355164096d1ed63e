#pragma once
/// \file session_to_stokes.h
/// `tirpol reduce` for a rotating-polarizer session: with a radiometric calibration the whole
/// chain (run_calibration_chain) to a calibrated Stokes EXR, without one the counts quick look
/// (reduce_session_counts); the EXR, the PNG quick looks, and the summary of what was written.

#include <cstddef>
#include <optional>
#include <string>

#include "tirpol/core/image.h"

namespace tirpol::calibration {

/// The session, the calibration files ("" calibration = counts quick look; the other options
/// then must stay off), the reduction switches and the files to write.
struct SessionToStokesOptions {
    std::string session;
    std::string calibration;   ///< radiometric calibration EXR, or ""
    std::string polarimetric;  ///< polarimetric calibration YAML, or ""
    std::string output;        ///< Stokes EXR
    std::string quicklooks;    ///< folder for S0/S1/S2/DoLP/AoP PNGs, or ""
    bool update_offset = false;
    bool drift_correction = false;
    bool slar = false;
    bool other_camera = false;
    double max_saturated_fraction = 0.01;
};

/// The drift correction applied, from the Stokes EXR's attributes.
struct DriftSummary {
    std::string source;
    double min_shift_counts = 0.0, max_shift_counts = 0.0;
    std::size_t records = 0;
    double max_sigma_counts = 0.0;
};

/// What session_to_stokes wrote.
struct SessionToStokes {
    std::string output;
    bool counts_quicklook = false;  ///< no calibration: counts, not radiance
    int width = 0, height = 0;
    ChannelStats s0, dolp;
    int saturated_pixels = 0;
    int unrealizable_pixels = 0;                      ///< calibrated reduction only
    std::optional<std::string> calibration_warnings;  ///< calibrated reduction only
    std::optional<DriftSummary> drift;                ///< with drift_correction
};

/// The quick-look file names of a Stokes folder, for output guards.
inline constexpr const char* kStokesQuicklookFiles[] = {"S0.png", "S1.png", "S2.png", "DoLP.png",
                                                        "AoP.png"};

/// Reduces the session and writes the Stokes EXR and the quick looks asked for. Throws
/// tirpol::Error naming the session or calibration for what does not read or fit.
SessionToStokes session_to_stokes(const SessionToStokesOptions& options);

/// What `tirpol reduce` checks before any work: without a calibration the calibrated-reduction
/// switches (polarimetric, update_offset, drift_correction, slar, other_camera) must stay off
/// (tirpol::OptionValueError naming the first one given), and no output may replace an input or,
/// unless `force`, an existing file (OutputGuard).
void check_session_to_stokes(const SessionToStokesOptions& options, bool force);

/// The summary: for a counts quick look its label and a line in counts; else the calibration
/// warnings, the drift correction and a line in radiance.
std::string session_to_stokes_text(const SessionToStokes& reduction);

}  // namespace tirpol::calibration
