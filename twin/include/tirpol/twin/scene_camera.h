#pragma once
/// \file scene_camera.h
/// The renderer-backed camera of ARCHITECTURE.md, `sim://<scene.yaml>`, plugged into acquisition's
/// camera registry from here because acquisition must not depend on simulation:
///   sim://<scene.yaml>[?width=W&height=H&spp=N&fps=F&buffers=Q&microgrid=P&seed=S]
/// The scene is rendered once when the camera opens (its own camera, resized to W×H; N samples per
/// pixel); every frame is then the twin instrument's detector looking at that Stokes image through
/// the wire grid at the polarizer angle (0° until acquisition::couple_simulated_polarizer puts it
/// behind a stage, as `tirpol acquire` and `tirpol live` do): counts of twin_sensor(), with a fresh
/// temporal-noise realisation per frame. With `microgrid=sony` (or four angles, cell positions
/// (0,0) (0,1) (1,0) (1,1)) it is a microgrid (DoFP) camera instead: every frame is the rendered
/// image through simulation/dofp_sensor.h's sensor (DofpSensorSpec's defaults with that pattern,
/// the array drawn from seed S, default 1; even W and H), the pattern in its CameraInfo, polarized
/// pixel formats offered, no polarizer turning. A relative path is taken from the working directory
/// and, when it starts with `config/` and is not there, from the source tree's config/ folder.
/// Other `sim://` targets (sim://uniform) go to the factory registered before.

#include <memory>
#include <string>

#include "tirpol/acquisition/camera.h"

namespace tirpol::twin {

/// Registers the twin's device schemes (sim://<scene.yaml> cameras) with acquisition's registries.
/// Idempotent and thread-safe; the CLI calls it at start-up.
void register_twin_device_schemes();

/// Opens a `sim://<scene.yaml>` camera (what the registered factory calls). Throws tirpol::Error
/// for a malformed URI or scene file, naming it.
std::unique_ptr<acquisition::Camera> open_scene_camera(const std::string& uri);

}  // namespace tirpol::twin
