#include "tirpol/calibration/microgrid_run.h"

#include <fmt/format.h>

#include <optional>

#include "microgrid_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/core/quicklook.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/core/session.h"

namespace tirpol::calibration {

DemosaicRun run_demosaic(const DemosaicRunOptions& o) {
    OutputGuard().input(o.input, "INPUT").output_file(o.output, "--output").check(o.force);
    std::optional<MicrogridPattern> pattern;
    if (!o.pattern.empty())
        pattern =
            parse_option_value("--pattern", [&] { return MicrogridPattern::parse(o.pattern); });
    MicrogridReductionOptions options;
    options.method =
        parse_option_value("--method", [&] { return parse_demosaic_method(o.method); });
    const MicrogridFileReduction reduced =
        reduce_microgrid_file(o.input, pattern, options, o.channel);
    write_exr(o.output, reduced.stokes);
    DemosaicRun run;
    run.output = o.output;
    run.width = reduced.stokes.width();
    run.height = reduced.stokes.height();
    run.method = options.method;
    run.pattern = reduced.pattern.text();
    run.units = reduced.units;
    run.s0_mean = channel_stats(reduced.stokes.channel("S0")).mean;
    run.dolp_mean = channel_stats(reduced.stokes.channel("DoLP")).mean;
    run.unrealizable_pixels = reduced.unrealizable_pixels;
    return run;
}

std::string demosaic_run_text(const DemosaicRun& r) {
    return fmt::format(
        "Stokes {}×{} ({}, pattern {}): S0 mean {:.6g} {}, DoLP mean {:.4f}; {} unrealizable "
        "pixel(s) projected → {}\n",
        r.width, r.height, demosaic_method_name(r.method), r.pattern, r.s0_mean, r.units,
        r.dolp_mean, r.unrealizable_pixels, r.output.string());
}

bool is_readable_microgrid_session(const std::filesystem::path& session) {
    try {
        return std::filesystem::exists(session / kSessionManifestName) &&
               is_microgrid_session(session);
    } catch (const Error&) {
        return false;
    }
}

MicrogridReduceRun run_microgrid_reduction(const MicrogridReduceRunOptions& o) {
    OutputGuard()
        .input(o.session, "SESSION")
        .input(o.pixel_calibration, "--pixel-calibration")
        .output_file(o.output, "--output")
        .output_folder(o.quicklooks, "--quicklooks",
                       {"S0.png", "S1.png", "S2.png", "DoLP.png", "AoP.png"})
        .check(o.force);
    MicrogridSessionOptions options;
    options.method =
        parse_option_value("--method", [&] { return parse_demosaic_method(o.method); });
    if (!o.pixel_calibration.empty())
        options.pixel_calibration =
            MicrogridPixelCalibration::from_image(read_exr(o.pixel_calibration));
    Image stokes = reduce_microgrid_session(o.session, options);
    if (!o.pixel_calibration.empty())
        stokes.attributes()["pixel_calibration"] = o.pixel_calibration;
    write_exr(o.output, stokes);
    MicrogridReduceRun run;
    run.output = o.output;
    run.width = stokes.width();
    run.height = stokes.height();
    const MicrogridSessionRecord recorded = microgrid_session_record(stokes);
    run.frames_averaged = recorded.frames_averaged;
    run.pattern = recorded.pattern.text();
    run.reduction = o.pixel_calibration.empty() ? std::string(demosaic_method_name(options.method))
                                                : "per-pixel calibration";
    run.units = recorded.units.empty() ? "(units not recorded)" : recorded.units;
    run.s0_mean = channel_stats(stokes.channel("S0")).mean;
    run.dolp_mean = channel_stats(stokes.channel("DoLP")).mean;
    if (!o.quicklooks.empty())
        for (const std::string c : {"S0", "S1", "S2", "DoLP", "AoP"})
            write_quicklook(std::filesystem::path(o.quicklooks) / (c + ".png"), stokes.channel(c),
                            stokes.width(), stokes.height(),
                            channel_quicklook_options(c, run.units));
    return run;
}

std::string microgrid_reduce_run_text(const MicrogridReduceRun& r) {
    return fmt::format(
        "Stokes {}×{} (microgrid {}, {}, {} frame(s)): S0 mean {:.6g} {}, DoLP mean {:.4f} → {}\n",
        r.width, r.height, r.pattern, r.reduction, r.frames_averaged, r.s0_mean, r.units,
        r.dolp_mean, r.output.string());
}

MicrogridCalibrationRun run_microgrid_calibration(const MicrogridCalibrationRunOptions& o) {
    OutputGuard guard;
    for (const auto& session : o.sessions) guard.input(session, "SESSION");
    guard.input(o.rsr, "--rsr").output_file(o.output, "--output").check(o.force);
    const auto [lo_um, hi_um] = o.band_um;
    if (!(lo_um > 0.0 && hi_um > lo_um))
        throw OptionValueError(
            "--band-um",
            fmt::format("--band-um {} {}: expected 0 < LO < HI micrometres", lo_um, hi_um));
    std::optional<SpectralResponse> rsr;
    if (!o.rsr.empty()) rsr = SpectralResponse::load_csv(o.rsr);
    MicrogridCalibrationRun run;
    run.output = o.output;
    run.calibration = calibrate_microgrid_sessions({o.sessions.begin(), o.sessions.end()},
                                                   Band(lo_um, hi_um, rsr));
    Image image = run.calibration.pixels.to_image();
    write_stokes_image_header(image, {.band_um = std::array{lo_um, hi_um}});
    write_exr(o.output, image);
    return run;
}

std::string microgrid_calibration_text(const MicrogridCalibrationRun& run) {
    const MicrogridFlatFieldCalibration& r = run.calibration;
    const MicrogridPixelCalibration& cal = r.pixels;
    std::string text = fmt::format(
        "microgrid calibration {}×{} from {} open-blackbody and {} polarizer record(s)\n",
        cal.width, cal.height, r.open_blackbody_records, r.polarizer_records);
    text += fmt::format("  two-point NUC: gain spread {:.2f} %, fit RMS {:.3g} counts\n",
                        100.0 * r.gain_rel_spread, r.nuc_fit_rms_counts);
    text += fmt::format(
        "  analyzers: diattenuation median {:.4f} (robust σ {:.4f}), axis error RMS {:.2f}°, fit "
        "RMS {:.3g} counts\n",
        r.diattenuation_median, r.diattenuation_spread, r.axis_error_rms_deg, cal.fit_rms);
    text += fmt::format(
        "  bad pixels: {} (dead {}, hot {}, noisy {}, non-linear {}, saturated {}, bad analyzer "
        "{})\n",
        r.bad_count(), r.bad_count(kDead), r.bad_count(kHot), r.bad_count(kNoisy),
        r.bad_count(kNonLinear), r.bad_count(kSaturated), r.bad_count(kBadAnalyzer));
    return text + fmt::format("→ {}\n", run.output.string());
}

}  // namespace tirpol::calibration
