// The microgrid camera's world in the twin: what the DoFP detector sees at each moment of a
// flat-field session — the blackbody behind the reference polarizer (Malus's law per pixel through
// the polarizer's diattenuation, plus its own emission), the operator's open blackbody held in
// front of the lens until the stage next moves, and the scene without the polarizer.

#include <gtest/gtest.h>

#include <cmath>

#include "tirpol/core/error.h"
#include "tirpol/twin/instrument.h"

namespace tirpol::twin {
namespace {

simulation::DofpSensor noiseless_sensor(const Band& band) {
    simulation::DofpSensorSpec spec;
    spec.nedt_k = 0.0;
    spec.spread.axis_sigma_deg = 3.0;
    return simulation::DofpSensor(spec, 8, 6, band);
}

TEST(DofpWorld, FlatFieldRigFollowsMalusThroughTheReferencePolarizer) {
    const Band band(8.0, 14.0);
    ReferencePolarizer reference;  // τ 0.85, extinction 1000, emission 1.5 W/(m² sr)
    TwinWorld world(noiseless_sensor(band), reference, band);
    ASSERT_TRUE(world.microgrid_pattern_deg());
    EXPECT_EQ((*world.microgrid_pattern_deg())[0], 90.0);
    const simulation::DofpPixels& pixels = world.dofp()->pixels();
    const double l = band.radiance(323.15);
    world.set_flat_field_backdrop(323.15);
    for (double phi : {0.0, 30.0, 95.0}) {
        std::vector<float> counts(48);
        world.fill(phi, counts);
        for (std::size_t i = 0; i < counts.size(); ++i) {
            // A pixel of axis θ, diattenuation d, gain g behind a polarizer of principal
            // transmittances τ, τ/ER at φ (unpolarized blackbody L, emission E):
            // g·[½L((τ + τ_min) + d(τ − τ_min) cos 2(φ − θ)) + E] + o.
            const double tau = reference.transmission, tau_min = tau / reference.extinction_ratio;
            const double g = pixels.responsivity[i] * 0.5 * pixels.transmission[i];
            const double c = std::cos(2.0 * (phi - pixels.axis_deg[i]) * M_PI / 180.0);
            const double want =
                g * (0.5 * l * ((tau + tau_min) + pixels.diattenuation[i] * (tau - tau_min) * c) +
                     reference.emitted_radiance) +
                pixels.offset_counts[i];
            EXPECT_NEAR(counts[i], want, 0.51) << "φ " << phi << " pixel " << i;
        }
    }
}

TEST(DofpWorld, OperatorBlackbodyIsSeenOpenUntilTheStageMovesThenTheScene) {
    const Band band(8.0, 14.0);
    TwinWorld world(noiseless_sensor(band), ReferencePolarizer{}, band);
    Image scene(8, 6);
    scene.add_channel("S0", 20.0f);
    for (const char* c : {"S1", "S2", "S3"}) scene.add_channel(c, 0.0f);
    world.set_scene(scene);
    const simulation::DofpPixels& pixels = world.dofp()->pixels();
    const double l = band.radiance(300.0);
    world.place_blackbody(300.0);
    world.on_stage_move();  // the step's move: the blackbody is in view
    std::vector<float> counts(48);
    world.fill(45.0, counts);
    for (std::size_t i = 0; i < counts.size(); ++i)
        EXPECT_NEAR(
            counts[i],
            pixels.responsivity[i] * 0.5 * pixels.transmission[i] * l + pixels.offset_counts[i],
            0.51);
    world.on_stage_move();  // the next move: the operator took it away
    world.fill(45.0, counts);
    for (std::size_t i = 0; i < counts.size(); ++i)
        EXPECT_NEAR(
            counts[i],
            pixels.responsivity[i] * 0.5 * pixels.transmission[i] * 20.0 + pixels.offset_counts[i],
            0.51);
    Image wrong(4, 4);
    EXPECT_THROW(world.set_scene(wrong), Error);
}

}  // namespace
}  // namespace tirpol::twin
