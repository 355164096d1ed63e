#pragma once
/// \file counts_quicklook.h
/// A Stokes quick look of a rotating-polarizer session in raw counts, when no radiometric
/// calibration exists yet (the first night in the field): each angle's scene records averaged and
/// reduced with ideal analyzers at the angles the stage read back (paper eqs 14–16). It is
/// labelled counts, not radiance: the detector offset stays in S0 (an offset common to the angles
/// cancels in S1 = I0 − I90 and S2 = I45 − I135), and neither the per-pixel gain nor the
/// polarizer's own emission and reflections (the wire-grid terms) are removed, so DoLP and AoP are
/// biased where those matter. For aiming and a first look; not for a comparison with a simulation.

#include <atomic>
#include <filesystem>

#include "tirpol/core/image.h"

namespace tirpol::calibration {

struct CountsQuicklookOptions {
    /// Saturated scene pixels become NaN; more than this fraction of any image is an error.
    double max_saturated_fraction = 0.01;
    /// Checked before each record is read: once set, throws tirpol::Cancelled. Null: never.
    const std::atomic<bool>* cancel = nullptr;
};

/// Text of the `calibration` attribute a counts quick look carries (and the CLI prints).
inline constexpr const char* kCountsQuicklookLabel =
    "counts quick look: no radiometric or polarimetric calibration applied; counts, not radiance";

/// Reduces the session's polarizer records (those of a `metadata.known_source` repeat excluded) to
/// S0 S1 S2 DoLP AoP and their *_std (the frame scatter over √frames, propagated) in counts.
/// Attributes: units "counts", calibration = kCountsQuicklookLabel, analyzer, session, camera,
/// saturated_pixels, std_includes, and those of reduce_stokes. Throws tirpol::Error naming the
/// manifest for a session without polarizer records or with fewer than 3 angles, and naming the
/// frame for one over the saturated fraction.
Image reduce_session_counts(const std::filesystem::path& dir,
                            const CountsQuicklookOptions& options = {});

}  // namespace tirpol::calibration
