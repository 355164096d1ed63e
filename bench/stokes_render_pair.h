#pragma once
/// \file stokes_render_pair.h
/// Two renders of one scene with independent seeds, and the relative linear-polarization noise
/// measured from them: shared by the simulation benchmarks and the Mitsuba 3 comparison
/// (mitsuba_comparison.cpp), so that both renderers' noise is measured the same way.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "tirpol/core/error.h"
#include "tirpol/core/image.h"
#include "tirpol/simulation/scene.h"

namespace tirpol::bench {

/// The Stokes channels of a render, in order.
inline const std::array<std::string, 4> kStokesChannels = {"S0", "S1", "S2", "S3"};

/// Two renders of one renderer with independent seeds, channels S0..S3 in tirpol's image Stokes
/// frame.
struct RenderPair {
    Image a, b;
    double seconds =
        0.0;  ///< per render: the sample loop's wall time (scene loading, tables excluded)
    double cpu_seconds =
        0.0;  ///< per render, summed over threads (tirpol: pixel loop; Mitsuba: process)
    int samples_per_pixel = 0;  ///< as rendered (Mitsuba's samplers round some counts up)
};

/// Relative linear-polarization noise of one render of `p` over the pixels `mask`:
/// √(mean over pixels of ((a−b)²/2 in S1 and S2)) / mean S0.
inline double relative_linear_noise(const RenderPair& p, const std::vector<bool>& mask) {
    double var = 0.0, s0 = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i]) continue;
        for (const char* c : {"S1", "S2"}) {
            const double d = p.a.channel(c)[i] - p.b.channel(c)[i];
            var += 0.5 * d * d;
        }
        s0 += 0.5 * (p.a.channel("S0")[i] + p.b.channel("S0")[i]);
        ++n;
    }
    return std::sqrt(var / static_cast<double>(n)) / (s0 / static_cast<double>(n));
}

/// The pixels whose centre ray hits a surface (noise_objects empty) or one of noise_objects.
inline std::vector<bool> noise_mask(const simulation::Scene& scene, const Image& ids,
                                    const std::vector<std::string>& noise_objects) {
    std::vector<bool> measured(scene.objects.size(), noise_objects.empty());
    for (const auto& name : noise_objects) {
        const auto it =
            std::find_if(scene.objects.begin(), scene.objects.end(),
                         [&](const simulation::SceneObject& o) { return o.name == name; });
        if (it == scene.objects.end())
            throw Error(scene.file.string() + ": no object named " + name + " to measure noise on");
        measured[static_cast<std::size_t>(it - scene.objects.begin())] = true;
    }
    std::vector<bool> mask(ids.pixel_count());
    for (std::size_t i = 0; i < mask.size(); ++i) {
        const float id = ids.channel("object_id")[i];
        mask[i] = id >= 0.0f && measured[static_cast<std::size_t>(id)];
    }
    return mask;
}

}  // namespace tirpol::bench
