#include <fmt/format.h>
#include <fmt/printf.h>

#include <algorithm>
#include <filesystem>

#include "counts_quicklook.h"
#include "tirpol/calibration/calibration_chain.h"
#include "tirpol/calibration/polarimetric_file.h"
#include "tirpol/calibration/stokes_reduction.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/core/quicklook.h"

namespace tirpol::calibration {

namespace {
void write_stokes_quicklooks(const std::string& folder, const Image& stokes, bool counts) {
    if (folder.empty()) return;
    for (const std::string c : {"S0", "S1", "S2", "DoLP", "AoP"}) {
        QuicklookOptions q =
            counts ? channel_quicklook_options(c, "counts") : channel_quicklook_options(c);
        if (counts) q.title = c + " (counts quick look, uncalibrated)";
        write_quicklook(std::filesystem::path(folder) / (c + ".png"), stokes.channel(c),
                        stokes.width(), stokes.height(), q);
    }
}

Image reduce_with_calibration(const SessionToStokesOptions& o) {
    ChainInputs chain;
    chain.scene_sessions = {o.session};
    chain.reduction.update_offset = o.update_offset;
    chain.reduction.drift_correction = o.drift_correction;
    chain.reduction.max_saturated_fraction = o.max_saturated_fraction;
    chain.reduction.include_slar = o.slar;
    chain.reduction.force_other_camera = o.other_camera;
    Image stokes =
        run_calibration_chain(chain, read_calibration_products(o.calibration, o.polarimetric))
            .stokes.front();
    stokes.attributes()["radiometric_calibration"] = o.calibration;
    stokes.attributes()["polarimetric_calibration"] = o.polarimetric;
    return stokes;
}

std::optional<DriftSummary> drift_of(const Attributes& at) {
    const auto it = at.find("drift_offset_counts");
    if (it == at.end()) return std::nullopt;
    const auto& shift = std::get<std::vector<double>>(it->second);
    const auto& sigma = std::get<std::vector<double>>(at.at("drift_offset_sigma_counts"));
    const auto [lo, hi] = std::minmax_element(shift.begin(), shift.end());
    return DriftSummary{std::get<std::string>(at.at("drift_correction_source")), *lo, *hi,
                        shift.size(), *std::max_element(sigma.begin(), sigma.end())};
}
}  // namespace

SessionToStokes session_to_stokes(const SessionToStokesOptions& o) {
    SessionToStokes r;
    r.output = o.output;
    r.counts_quicklook = o.calibration.empty();
    CountsQuicklookOptions counts;
    counts.max_saturated_fraction = o.max_saturated_fraction;
    const Image stokes =
        r.counts_quicklook ? reduce_session_counts(o.session, counts) : reduce_with_calibration(o);
    write_exr(o.output, stokes);
    write_stokes_quicklooks(o.quicklooks, stokes, r.counts_quicklook);
    const Attributes& at = stokes.attributes();
    r.width = stokes.width();
    r.height = stokes.height();
    r.s0 = channel_stats(stokes.channel("S0"));
    r.dolp = channel_stats(stokes.channel("DoLP"));
    r.saturated_pixels = std::get<int>(at.at("saturated_pixels"));
    if (r.counts_quicklook) return r;
    r.unrealizable_pixels = stokes_reduction_record(stokes).unrealizable_pixels;
    if (const auto it = at.find("calibration_warnings"); it != at.end())
        r.calibration_warnings = std::get<std::string>(it->second);
    r.drift = drift_of(at);
    return r;
}

std::string session_to_stokes_text(const SessionToStokes& r) {
    if (r.counts_quicklook)
        return std::string(kCountsQuicklookLabel) + "\n" +
               fmt::sprintf(
                   "Stokes %d×%d in counts: S0 mean %.6g counts, DoLP mean %.4f; %d saturated → "
                   "%s\n",
                   r.width, r.height, r.s0.mean, r.dolp.mean, r.saturated_pixels, r.output);
    std::string text =
        r.calibration_warnings ? fmt::sprintf("warning: %s\n", *r.calibration_warnings) : "";
    if (r.drift)
        text += fmt::sprintf(
            "drift correction (%s): offset shift %.2f … %.2f counts over %zu records, σ ≤ %.3f "
            "counts\n",
            r.drift->source, r.drift->min_shift_counts, r.drift->max_shift_counts, r.drift->records,
            r.drift->max_sigma_counts);
    return text + fmt::sprintf(
                      "Stokes %d×%d: S0 mean %.4g W/(m²·sr), DoLP mean %.4f; %d unrealizable "
                      "pixel(s) projected, %d saturated → %s\n",
                      r.width, r.height, r.s0.mean, r.dolp.mean, r.unrealizable_pixels,
                      r.saturated_pixels, r.output);
}

void check_session_to_stokes(const SessionToStokesOptions& o, bool force) {
    if (o.calibration.empty())  // no calibration: a quick look in counts, labelled so
        for (const auto& [given, name] :
             {std::pair{!o.polarimetric.empty(), "--polarimetric"},
              std::pair{o.update_offset, "--update-offset"},
              std::pair{o.drift_correction, "--drift-correction"}, std::pair{o.slar, "--slar"},
              std::pair{o.other_camera, "--other-camera"}})
            if (given)
                throw OptionValueError(
                    name, fmt::format("{} needs --calibration (without it reduce makes a counts "
                                      "quick look)",
                                      name));
    OutputGuard()
        .input(o.session, "SESSION")
        .input(o.calibration, "--calibration")
        .input(o.polarimetric, "--polarimetric")
        .input(o.polarimetric.empty() ? "" : polarimetric_maps_path(o.polarimetric),
               "--polarimetric maps")
        .output_file(o.output, "--output")
        .output_folder(o.quicklooks, "--quicklooks",
                       {std::begin(kStokesQuicklookFiles), std::end(kStokesQuicklookFiles)})
        .check(force);
}

}  // namespace tirpol::calibration
