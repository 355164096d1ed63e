// Paper eq 17 on rendered Stokes images, where its assumption holds: the panels of panels_night in
// uniform surroundings (a uniform 250 K sky, ground and rack at 250 K). Then the downwelling every
// surface sees is L_BB(250 K) from every direction, so S = ε·L_BB(T) + (1 − ε)·L_dw per Stokes
// component (Kirchhoff: the polarized reflectance of uniform unpolarized light is −ε_S1), and the
// extraction must return the paint's own directional emissivity (Gartley et al. eq 5) in every
// view. The diffuse IR reflector stays at 5 °C: its own emission (ε_r = 1 − DHR, 0.03–0.12 over
// these views) must be removed from L_dw, or ε_S0 comes out far too low. This pins the renderer's
// polarized emission and reflection to the extraction's algebra; under the real clear sky the two
// differ by eq 17's bias (docs/twin.md), which this test rules out as a renderer error.

#include <gtest/gtest.h>

#include <cmath>

#include "regions.h"
#include "tirpol/calibration/emissivity_extraction.h"
#include "tirpol/core/geometry.h"
#include "tirpol/core/source_tree.h"
#include "tirpol/materials/emissivity.h"
#include "tirpol/simulation/renderer.h"
#include "tirpol/simulation/scene.h"

namespace tirpol::twin {
namespace {

constexpr double kSurroundingsK = 250.0;
constexpr double kWavelengthUm = 10.0;  // the paint's n, k are constant over the band

struct ViewResult {
    double view_angle_deg = 0.0;
    PlaneOfEmissionEmissivity corrected, uncorrected;
    double true_s0 = 0.0, true_s1 = 0.0;
};

simulation::Scene uniform_surroundings() {
    simulation::Scene scene = simulation::load_scene(find_config("scenes/panels_night.yaml"));
    scene.sky = simulation::Sky::uniform(kSurroundingsK);
    for (auto& o : scene.objects)
        if (o.name.rfind("panel_", 0) != 0)
            o.temperature = simulation::TemperatureField::constant(kSurroundingsK);
    scene.sampling.samples_per_pixel = 32;
    return scene;
}

ViewResult extract_in_view(const simulation::Scene& base, const Vec3& position) {
    simulation::Scene scene = base;
    const simulation::PinholeCamera resized = base.camera.resized(160, 128);
    const Vec3 look_at(0.0, -0.0208, 1.1017);  // the twin's views all look here
    scene.camera = simulation::PinholeCamera(
        resized.width(), resized.height(), resized.intrinsics(), position,
        simulation::PinholeCamera::look_at(position, look_at, Vec3(0.0, 0.0, 1.0)));
    const Image render = simulation::render(scene, {});
    const std::size_t target = object_index(scene, "panel_flat_black_paint");
    const std::size_t reflector = object_index(scene, "panel_diffuse_ir_reflector");
    const auto target_rect = object_rect(render, target);
    const auto reflector_rect = object_rect(render, reflector);
    EXPECT_TRUE(target_rect && reflector_rect);
    if (!target_rect || !reflector_rect) return {};
    const auto mean_of = [&](const char* channel, const calibration::PixelRect& r) {
        return calibration::region_mean(render, channel, r, "test").mean;
    };
    const auto& materials = scene.materials;
    const double reflector_view_deg = mean_of("view_zenith_deg", *reflector_rect);
    calibration::EmissivityRois rois;
    rois.reflector = {*reflector_rect,
                      materials::directional_emissivity(
                          *materials[scene.objects[reflector].material].brdf,
                          std::cos(deg_to_rad(reflector_view_deg)), kWavelengthUm)(0),
                      0.0, mean_of("temperature_k", *reflector_rect), 0.0};
    calibration::EmissivityTarget t;
    t.name = "flat_black_paint";
    t.rect = *target_rect;
    t.view_angle_deg = mean_of("view_zenith_deg", *target_rect);
    t.temperature_k = mean_of("temperature_k", *target_rect);
    t.temperature_std_k = 0.0;  // the render's temperature is exact: σ is the ROI's scatter alone
    rois.targets.push_back(t);

    const double psi = plane_of_emission_angle(render, scene.camera, *target_rect);
    ViewResult r;
    r.view_angle_deg = t.view_angle_deg;
    r.corrected = in_plane_of_emission(
        calibration::extract_emissivity(render, rois, scene.band).front(), psi);
    rois.reflector.emissivity = 0.0;  // the paper's perfect reflector
    r.uncorrected = in_plane_of_emission(
        calibration::extract_emissivity(render, rois, scene.band).front(), psi);
    const StokesVector truth =
        materials::directional_emissivity(*materials[scene.objects[target].material].brdf,
                                          std::cos(deg_to_rad(t.view_angle_deg)), kWavelengthUm);
    r.true_s0 = truth(0);
    r.true_s1 = truth(1);
    return r;
}

TEST(Eq17UniformSurroundings, ExtractionReturnsThePaintsEmissivityInEveryView) {
    const simulation::Scene scene = uniform_surroundings();
    // The twin's three camera positions: the paint panel seen ≈ 58°, 41° and 25° off its normal.
    for (const Vec3& position :
         {Vec3(0.0, -6.0, 1.6), Vec3(0.0, -5.0, 3.4), Vec3(0.0, -3.8, 4.6)}) {
        const ViewResult r = extract_in_view(scene, position);
        SCOPED_TRACE(::testing::Message() << "view angle " << r.view_angle_deg << "°");
        const auto& e = r.corrected;
        EXPECT_LT(std::abs(e.eps_s0 - r.true_s0), 4.0 * e.eps_s0_std + 1e-4)
            << e.eps_s0 << " vs " << r.true_s0;
        EXPECT_LT(std::abs(e.eps_s1 - r.true_s1), 4.0 * e.eps_s1_std + 1e-4)
            << e.eps_s1 << " vs " << r.true_s1;
        EXPECT_LT(std::abs(e.eps_s1 - r.true_s1), 0.05 * std::abs(r.true_s1));  // 5 % of ε_S1
        EXPECT_LT(r.true_s1, 0.0);  // p-polarized emission
        // Without removing the warm reflector's emission L_dw is too high and ε_S0 far too low.
        EXPECT_LT(r.uncorrected.eps_s0, r.true_s0 - 8.0 * e.eps_s0_std);
    }
}

}  // namespace
}  // namespace tirpol::twin
