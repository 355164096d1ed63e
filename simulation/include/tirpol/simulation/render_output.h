#pragma once
/// \file render_output.h
/// Writing a rendered Stokes image: the EXR (all channels and header attributes) and PNG quicklooks
/// of S0, S1, S2, DoLP, AoP and temperature; and the whole of `tirpol render` (a scene file with
/// the command line's overrides, rendered into a folder) as one call.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/core/image.h"
#include "tirpol/simulation/renderer.h"

namespace tirpol::simulation {

/// Writes `<out_dir>/<stem>.exr` and `<out_dir>/<stem>_<channel>.png` for the quicklook channels;
/// returns the paths written. Atomic writes; creates `out_dir`.
std::vector<std::filesystem::path> write_render_outputs(const std::filesystem::path& out_dir,
                                                        const std::string& stem,
                                                        const Image& image);

/// `tirpol render`: a scene file, the overrides of its settings, and the output folder.
struct RenderRunOptions {
    std::filesystem::path scene;   ///< scene YAML (docs/scene-format.md)
    std::filesystem::path output;  ///< folder of `<stem>.exr` and its quicklooks
    /// Overrides of the scene's sampling and camera; none: the scene's.
    std::optional<int> samples_per_pixel, width, height, max_bounces;
    std::optional<std::uint64_t> seed;
    std::string estimator;         ///< "plain" or "control-variate"; empty: the scene's
    std::filesystem::path sensor;  ///< sensor-model YAML: also `<stem>_pol<angle>.exr`; empty: none
    int threads = 0;               ///< 0: all cores (the image does not depend on it)
    bool show_progress = true;
    bool force = false;  ///< existing outputs may be replaced (OutputGuard)
};

/// What run_render did.
struct RenderRun {
    std::filesystem::path scene;
    int width = 0, height = 0;
    int samples_per_pixel = 0;  ///< rendered (rendered_samples_per_pixel)
    int replicates = 0;
    RenderStatistics statistics;
    std::vector<std::filesystem::path> polarizer_images;  ///< with RenderRunOptions::sensor
    std::vector<std::filesystem::path> written;           ///< the EXR and its quicklooks
};

/// Loads the scene, applies the overrides (tirpol::OptionValueError naming the option for a value
/// the scene cannot take: one of width/height, a size below 1, spp below 1, a bounce cap out of
/// range, an unknown estimator), checks the outputs (OutputGuard), renders and writes.
RenderRun run_render(const RenderRunOptions& options);

/// The summary `tirpol render` prints: the polarizer images, the render's size, samples, time and
/// speed, then the files written.
std::string render_run_text(const RenderRun& run);

}  // namespace tirpol::simulation
