// Synthetic sessions honour the caller's band: the grid's sky reflection and emission are band
// radiances over that band (they used to be computed over 8–14 µm whatever the band), so a dark
// scene seen through the polarizer in the MWIR gives counts o + g·(ρ·L(T_sky) + ε·L(T_grid)) with L
// Planck's law integrated over 3–5 µm.

#include "tirpol/calibration/synthetic_session.h"

#include <gtest/gtest.h>

namespace tirpol::calibration {
namespace {

TEST(SyntheticSession, GridTermsAreIntegratedOverTheCallersBand) {
    SyntheticCamera cam;
    cam.gain_rel_std = 0.0, cam.offset_std = 0.0, cam.noise_counts = 0.0, cam.ghost_radiance = 0.0;
    cam.sky_polarization = 0.0;
    Image dark(cam.width, cam.height);
    for (const char* c : {"S0", "S1", "S2"}) dark.add_channel(c);
    const std::size_t centre = dark.index(cam.width / 2, cam.height / 2);
    for (const Band& band : {Band(3.0, 5.0), Band(8.0, 14.0)}) {
        const double grid = cam.grid_reflectance * band.radiance(cam.sky_temperature_k) +
                            cam.grid_emissivity * band.radiance(cam.grid_temperature_k);
        const Image frame = synthetic_record_frame(cam, dark, band, 0.0, true, false, 3);
        EXPECT_NEAR(frame.channel("counts")[centre], cam.offset_mean + cam.gain_mean * grid, 1e-3)
            << band.lo_um() << "–" << band.hi_um() << " µm";
    }
    // The two bands differ by far more than the tolerance: the check above tells them apart.
    EXPECT_GT(cam.gain_mean * cam.grid_reflectance *
                  (Band(8.0, 14.0).radiance(cam.sky_temperature_k) -
                   Band(3.0, 5.0).radiance(cam.sky_temperature_k)),
              10.0);
}

}  // namespace
}  // namespace tirpol::calibration
