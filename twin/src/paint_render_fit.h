#pragma once
// The twin's fit of the target paint through the renderer (fitting/render_fit.h), beside eq 17's.

#include <cstdint>
#include <vector>

#include "tirpol/core/image.h"
#include "tirpol/simulation/pinhole_camera.h"
#include "tirpol/simulation/scene.h"
#include "tirpol/twin/twin.h"

namespace tirpol::twin {

struct PaintRenderFitInputs {
    const simulation::Scene* scene = nullptr;  ///< the true scene (its sky, temperatures, geometry)
    std::vector<simulation::PinholeCamera>
        cameras;  ///< the camera of each view, as the fit renders it
    const std::vector<Image>* measured = nullptr;  ///< reduced Stokes per view (S*, S*_std)
    const std::vector<Image>* truth = nullptr;  ///< truth renders per view (regions, their S*_var)
    std::size_t target_object = 0;
    std::uint32_t target_material = 0;
    double initial_n = 1.5, initial_sigma = 0.2;  ///< the eq-17 fit: the first guess
    double true_n = 0.0, true_sigma = 0.0;
    std::uint64_t seed = 1;
    int samples_per_pixel = 32;  ///< of the fit's renders (only the regions' pixels are traced)
    int threads = 0;
};

/// Fits n and σ of the target's material to the measured Stokes of the target and of every other
/// object of the same material, in every view.
/// The measured σ is the reduction's S*_std with the truth render's Monte Carlo variance added (the
/// twin's measurement observes that render, so it carries its noise).
TwinRenderFit fit_paint_through_renderer(const PaintRenderFitInputs& in);

}  // namespace tirpol::twin
