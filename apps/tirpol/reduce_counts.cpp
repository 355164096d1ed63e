// `tirpol reduce SESSION -o OUT` without --calibration: a Stokes quick look in counts.

#include "reduce_counts.h"

#include <cstdio>

#include "tirpol/calibration/counts_quicklook.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/core/quicklook.h"

namespace tirpol::cli {

void run_reduce_counts(const CountsQuicklookArgs& a) {
    OutputGuard()
        .input(a.session, "SESSION")
        .output_file(a.output, "--output")
        .output_folder(a.quicklooks, "--quicklooks",
                       {"S0.png", "S1.png", "S2.png", "DoLP.png", "AoP.png"})
        .check(a.force);
    calibration::CountsQuicklookOptions options;
    options.max_saturated_fraction = a.max_saturated_fraction;
    const Image stokes = calibration::reduce_session_counts(a.session, options);
    write_exr(a.output, stokes);
    if (!a.quicklooks.empty())
        for (const char* c : {"S0", "S1", "S2", "DoLP", "AoP"}) {
            QuicklookOptions q = channel_quicklook_options(c, "counts");
            q.title = std::string(c) + " (counts quick look, uncalibrated)";
            write_quicklook(std::filesystem::path(a.quicklooks) / (std::string(c) + ".png"),
                            stokes.channel(c), stokes.width(), stokes.height(), q);
        }
    const auto s0 = channel_stats(stokes.channel("S0"));
    const auto dolp = channel_stats(stokes.channel("DoLP"));
    std::printf("%s\n", calibration::kCountsQuicklookLabel);
    std::printf("Stokes %d×%d in counts: S0 mean %.6g counts, DoLP mean %.4f; %d saturated → %s\n",
                stokes.width(), stokes.height(), s0.mean, dolp.mean,
                std::get<int>(stokes.attributes().at("saturated_pixels")), a.output.c_str());
}

}  // namespace tirpol::cli
