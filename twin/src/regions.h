#pragma once
/// \file regions.h
/// Regions of the twin's images from the truth render's geometry channels: the rectangle inside
/// an object's silhouette (object_id), its mean view angle, and the orientation of its plane of
/// emission in the image (for turning image-frame ε_S1, ε_S2 into the plane-of-emission ε_S1 the
/// fit expects).

#include <optional>
#include <string>

#include "tirpol/calibration/emissivity_extraction.h"
#include "tirpol/core/image.h"
#include "tirpol/simulation/pinhole_camera.h"
#include "tirpol/simulation/scene.h"

namespace tirpol::twin {

/// Index of the object called `name` in `scene`; throws tirpol::Error listing the names otherwise.
std::size_t object_index(const simulation::Scene& scene, const std::string& name);

/// The largest centred rectangle, shrunk from the silhouette's bounding box by whole pixels, whose
/// pixels all show object `object` (render channel object_id), with a one-pixel margin against
/// mixed edge pixels. nullopt when the object covers fewer than 4 such pixels.
std::optional<calibration::PixelRect> object_rect(const Image& render, std::size_t object);

/// Angle (radians) of the p direction of emission — the mean surface normal's component across the
/// ray through the rectangle's centre — in that ray's image Stokes frame (0° camera right, 90°
/// image top).
double plane_of_emission_angle(const Image& render, const simulation::PinholeCamera& camera,
                               const calibration::PixelRect& rect);

/// ε_S0 and ε_S1 of an extraction (σ = 1 standard uncertainty), ε_S1 rotated from the image frame
/// into the plane of emission whose p direction lies at `psi` (radians) in the image: there ε_S1 <
/// 0 is p-polarized emission, as fitting expects.
struct PlaneOfEmissionEmissivity {
    double eps_s0 = 0.0, eps_s0_std = 0.0, eps_s1 = 0.0, eps_s1_std = 0.0;
};
PlaneOfEmissionEmissivity in_plane_of_emission(const calibration::EmissivityResult& e, double psi);

}  // namespace tirpol::twin
