#pragma once
/// \file emissivity_csv.h
/// The measured polarized-emissivity CSV: `tirpol extract-emissivity` (calibration) writes it and
/// `tirpol fit` (fitting) reads it. Its schema, its writer and its reader are here and nowhere
/// else.
///
/// Header (this order; cells unquoted; `#` lines and blank lines are skipped):
///   name,view_angle_deg,temperature_k,pixels,l_dw_w_m2_sr,l_bb_w_m2_sr,frame,
///   eps_s0,eps_s0_std,eps_s1,eps_s1_std,eps_s2,eps_s2_std,wavelength_um
/// * `*_std`: standard (1σ) uncertainties — the one σ convention of the file.
/// * `frame`: the Stokes frame of eps_s1 and eps_s2 in that row:
///   `image` — the camera image frame (ARCHITECTURE.md: 0° along the image rows, S1 = I0 − I90),
///   what calibration measures; `plane_of_emission` — the s/p frame of the target's plane of
///   emission (materials/pbrdf.h: S1 < 0 for emission polarized in that plane), what a pBRDF
///   predicts.
/// * temperature_k, pixels, l_dw_w_m2_sr, l_bb_w_m2_sr, eps_s2, eps_s2_std and wavelength_um may be
///   empty (not measured / not known).
///
/// Older files still read (docs/fitting.md, "Older emissivity CSVs"):
/// * `eps_s0_2sigma`, `eps_s1_2sigma`, `eps_s2_2sigma` (2σ, the calibration writer before this
/// header)
///   are halved; the hand-written layout
///   `angle_deg,e_s0,e_s0_sigma,e_s1,e_s1_sigma[,wavelength_um][,name]` is 1σ.
/// * No `frame` column: each old writer's meaning — `image` for the `tirpol extract-emissivity`
/// layout;
///   `plane_of_emission` for the hand-written layout and for files with a `wavelength_um` column
///   (only fitting's writer, used by the digital twin, added it, and it wrote the plane-of-emission
///   frame).

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tirpol {

enum class EmissivityFrame { Image, PlaneOfEmission };

/// `image` / `plane_of_emission`.
std::string_view to_string(EmissivityFrame frame);

/// One row of the file (one target, or one view angle of one band).
struct EmissivityCsvRow {
    std::string name;                     ///< target / ROI name (no comma, no line break)
    double view_angle_deg = 0.0;          ///< emission angle from the surface normal
    std::optional<double> temperature_k;  ///< target temperature used for L_BB
    std::optional<std::size_t> pixels;    ///< pixels in the target ROI
    std::optional<double> l_dw_w_m2_sr;   ///< downwelled band radiance
    std::optional<double> l_bb_w_m2_sr;   ///< blackbody band radiance at the target temperature
    EmissivityFrame frame = EmissivityFrame::Image;
    double eps_s0 = 0.0, eps_s0_std = 0.0;
    double eps_s1 = 0.0, eps_s1_std = 0.0;     ///< in `frame`
    std::optional<double> eps_s2, eps_s2_std;  ///< in `frame`
    std::optional<double>
        wavelength_um;  ///< effective wavelength of the band (fits per wavelength)
    int line = 0;       ///< line in the file it was read from (0 when not read)
};

/// The CSV text (header above), numbers in shortest round-trip form. Throws tirpol::Error naming
/// the row for a name with a comma, quote or line break (the cell would split).
std::string emissivity_csv_text(const std::vector<EmissivityCsvRow>& rows);

/// Parses the CSV text (current or older layout, file comment). `source` names the file in errors.
/// Throws tirpol::Error naming source:line and the column for a missing required column, a wrong
/// cell count, a cell that is not a number or an unknown frame, and for more than
/// limits::kMaxCsvRows rows. Checks syntax only: whether the values are physical is the reader's
/// (fitting's) business.
std::vector<EmissivityCsvRow> parse_emissivity_csv(const std::string& text,
                                                   const std::string& source);

}  // namespace tirpol
