// Example: a Stokes test pattern (AoP sweeping across, DoLP growing downwards) seen through the
// paper's wire grid (extinction 400:1, §3.1) at 0/45/90/135°, reduced with the ideal eqs 14–16
// (calibration::reduce_stokes with an ideal analyzer model). The reduction error left by the
// non-ideal analyzer is what calibration's analyzer model removes.

#include "tirpol/calibration/analyzer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "examples.h"
#include "tirpol/calibration/stokes_reduction.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/geometry.h"
#include "tirpol/core/quicklook.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/core/stokes.h"

namespace tirpol::examples {

void analyzer_example(const std::filesystem::path& out_dir) {
    constexpr int kW = 180, kH = 120;
    const Band band(8.0, 14.0);
    const double s0 = band.radiance(300.0);
    const double angles_deg[4] = {0.0, 45.0, 90.0, 135.0};
    MuellerMatrix analyzer[4];
    for (int a = 0; a < 4; ++a)
        analyzer[a] = polarizer_with_extinction(deg_to_rad(angles_deg[a]), 0.7, 400.0);

    // Eqs 14–16 are W⁺ of an ideal polarizer (d = 1) at the four angles; the wire grid transmits
    // 70 %, which the reduction divides out.
    calibration::AnalyzerModel ideal = calibration::AnalyzerModel::ideal({0.0, 45.0, 90.0, 135.0});
    for (auto& position : ideal.positions) position.relative_transmission = 0.7;
    std::vector<calibration::AnalyzerImage> through_grid(4);
    for (int a = 0; a < 4; ++a) {
        through_grid[static_cast<std::size_t>(a)].angle_deg = angles_deg[a];
        through_grid[static_cast<std::size_t>(a)].signal.resize(std::size_t{kW} * kH);
    }
    Image truth(kW, kH);
    for (const char* c : {"S0", "S1", "S2", "DoLP", "AoP"}) truth.add_channel(c);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const double aop = kPi * x / kW, degree = 0.3 * y / (kH - 1);
            const StokesVector s = linearly_polarized(s0, degree, aop);
            const std::size_t i = truth.index(x, y);
            for (int a = 0; a < 4; ++a)
                through_grid[static_cast<std::size_t>(a)].signal[i] =
                    static_cast<float>((analyzer[a] * s)[0]);
            truth.channel("S0")[i] = static_cast<float>(s[0]);
            truth.channel("S1")[i] = static_cast<float>(s[1]);
            truth.channel("S2")[i] = static_cast<float>(s[2]);
            truth.channel("DoLP")[i] = static_cast<float>(dolp(s));
            truth.channel("AoP")[i] = static_cast<float>(aop_deg_0_180(s));
        }
    calibration::ReductionOptions as_measured;
    as_measured.project_to_realizable = false;
    Image measured = calibration::reduce_stokes(through_grid, kW, kH, ideal, nullptr, as_measured);
    double worst_dolp_error = 0.0;
    for (std::size_t i = 0; i < truth.channel("DoLP").size(); ++i)
        worst_dolp_error = std::max(
            worst_dolp_error,
            static_cast<double>(std::abs(measured.channel("DoLP")[i] - truth.channel("DoLP")[i])));
    for (auto* img : {&truth, &measured}) {
        write_stokes_image_header(*img, {.units = "W/(m^2 sr)", .band_um = std::array{8.0, 14.0}});
    }
    measured.attributes()["polarizer_extinction_ratio"] = 400.0;
    const auto dir = out_dir / "analyzer";
    write_exr(dir / "stokes_truth.exr", truth);
    write_exr(dir / "stokes_reduced_ideal_eqs.exr", measured);
    for (const char* c : {"S0", "S1", "S2", "DoLP", "AoP"}) {
        QuicklookOptions q;
        q.colormap = default_colormap(c);
        q.title = std::string(c) + " reduced";
        q.units = std::string(c) == "AoP" ? "°" : (std::string(c) == "DoLP" ? "" : "W/(m²·sr)");
        if (std::string(c) == "DoLP") {
            q.vmin = 0.0;
            q.vmax = 0.3;
        }
        write_quicklook(dir / (std::string(c) + ".png"), measured.channel(c), kW, kH, q);
    }
    std::printf("  400:1 wire grid, ideal reduction: worst DoLP error %.4f (of DoLP ≤ 0.3)\n",
                worst_dolp_error);
    std::printf("  images: %s/{stokes_truth,stokes_reduced_ideal_eqs}.exr and quicklooks *.png\n",
                dir.c_str());
}

}  // namespace tirpol::examples
