#include <fmt/printf.h>

#include <cmath>
#include <filesystem>

#include "tirpol/calibration/calibration_chain.h"
#include "tirpol/calibration/emissivity_extraction.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"

namespace tirpol::calibration {

namespace {
bool same_band(double lo_um, double hi_um, const Band& band) {
    return std::abs(lo_um - band.lo_um()) <= 1e-6 && std::abs(hi_um - band.hi_um()) <= 1e-6;
}
}  // namespace

std::vector<EmissivityResult> extract_emissivity(const EmissivityExtractionOptions& o) {
    OutputGuard()
        .input(o.input, "INPUT")
        .input(o.rois, "ROIS")
        .input(o.calibration, "--calibration")
        .input(o.polarimetric, "--polarimetric")
        .output_file(o.output, "--output")
        .check(o.force);
    ChainInputs chain;
    ChainProducts given;
    if (std::filesystem::is_directory(o.input)) {
        if (o.calibration.empty())
            throw OptionValueError(
                "--calibration",
                fmt::format("{} is a session: CAL.exr is needed to reduce it", o.input));
        given = read_calibration_products(o.calibration, o.polarimetric);
        chain.band = given.radiometric->band();
        if (o.band_um && !same_band(o.band_um->first, o.band_um->second, chain.band))
            fail(
                "--band-um {:g} {:g} differs from the band of the radiometric calibration {} "
                "({:g}–{:g} µm) that "
                "reduces the session; leave --band-um out, or calibrate in that band",
                o.band_um->first, o.band_um->second, o.calibration, chain.band.lo_um(),
                chain.band.hi_um());
        chain.scene_sessions = {o.input};
    } else {
        given.stokes = {read_exr(o.input)};
        const auto own = read_stokes_image_header(given.stokes.front(), o.input).band_um;
        if (o.band_um) {
            chain.band = Band(o.band_um->first, o.band_um->second);
            if (own && !same_band((*own)[0], (*own)[1], chain.band))
                fail(
                    "{}: its band_um ({:g}–{:g} µm) differs from --band-um {:g} {:g}; the Stokes "
                    "image's radiances "
                    "are in its own band: leave --band-um out",
                    o.input, (*own)[0], (*own)[1], o.band_um->first, o.band_um->second);
        } else if (own) {
            chain.band = Band((*own)[0], (*own)[1]);
        } else {
            fail("{}: no band_um attribute; give --band-um LO HI", o.input);
        }
    }
    chain.rois = {EmissivityRois::load(o.rois)};
    auto results = run_calibration_chain(chain, std::move(given)).emissivity.front();
    write_file_atomic(o.output, emissivity_csv(results));
    return results;
}

std::string emissivity_results_text(const std::vector<EmissivityResult>& results) {
    std::string text;
    for (const auto& r : results)
        text += fmt::sprintf(
            "  %-16s θ=%5.1f°  ε_S0 = %.4f ± %.4f  ε_S1 = %+.4f ± %.4f  ε_S2 = %+.4f ± %.4f (2σ)\n",
            r.name, r.view_angle_deg, r.eps_s0, 2.0 * r.eps_s0_std, r.eps_s1, 2.0 * r.eps_s1_std,
            r.eps_s2, 2.0 * r.eps_s2_std);
    return text;
}

}  // namespace tirpol::calibration
