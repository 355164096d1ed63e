// Demo step: a Stokes test pattern (AoP sweeping across, DoLP growing downwards) seen through the
// paper's wire grid (extinction 400:1, §3.1) at 0/45/90/135°, reduced with the ideal eqs 14–16. The
// reduction error left by the non-ideal analyzer is what calibration's analyzer model removes.

#include <cmath>
#include <cstdio>

#include "demo_steps.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/geometry.h"
#include "tirpol/core/mueller.h"
#include "tirpol/core/quicklook.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::cli {

namespace {
void demo_analyzer(const std::filesystem::path& out_dir) {
    constexpr int kW = 180, kH = 120;
    const Band band(8.0, 14.0);
    const double s0 = band.radiance(300.0);
    const double angles_deg[4] = {0.0, 45.0, 90.0, 135.0};
    MuellerMatrix analyzer[4];
    for (int a = 0; a < 4; ++a)
        analyzer[a] = polarizer_with_extinction(deg_to_rad(angles_deg[a]), 0.7, 400.0);

    Image truth(kW, kH), measured(kW, kH);
    for (const char* c : {"S0", "S1", "S2", "DoLP", "AoP"}) {
        truth.add_channel(c);
        measured.add_channel(c);
    }
    double worst_dolp_error = 0.0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const double aop = kPi * x / kW, degree = 0.3 * y / (kH - 1);
            const StokesVector s = linearly_polarized(s0, degree, aop);
            double intensity[4];
            for (int a = 0; a < 4; ++a) intensity[a] = (analyzer[a] * s)[0];
            // Eqs 14–16 assume an ideal polarizer of unit transmission; the wire grid transmits 70
            // %.
            const double t = 0.7;
            const StokesVector r{
                0.5 * (intensity[0] + intensity[1] + intensity[2] + intensity[3]) / t,
                (intensity[0] - intensity[2]) / t, (intensity[1] - intensity[3]) / t, 0.0};
            const std::size_t i = truth.index(x, y);
            for (auto* pair : {&truth, &measured}) {
                const StokesVector& v = pair == &truth ? s : r;
                pair->channel("S0")[i] = static_cast<float>(v[0]);
                pair->channel("S1")[i] = static_cast<float>(v[1]);
                pair->channel("S2")[i] = static_cast<float>(v[2]);
                pair->channel("DoLP")[i] = static_cast<float>(dolp(v));
                pair->channel("AoP")[i] = static_cast<float>(aop_deg_0_180(v));
            }
            worst_dolp_error = std::max(worst_dolp_error, std::abs(dolp(r) - dolp(s)));
        }
    for (auto* img : {&truth, &measured}) {
        img->attributes()["units"] = std::string("W/(m^2 sr)");
        img->attributes()["band_um"] = std::vector<double>{8.0, 14.0};
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

}  // namespace

TIRPOL_REGISTER_DEMO_STEP(
    150, "Polarimetry: a wire-grid analyzer at 0/45/90/135° and Stokes reduction (eqs 14–16)",
    demo_analyzer);

}  // namespace tirpol::cli
