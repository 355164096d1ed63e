// The calibration module's file-to-file runs (`tirpol noise`, `extract-emissivity`,
// `flir-temperature`, `temperature`) check their outputs against their inputs before they read
// anything: an output on an input's path is refused even with `force`, an existing file at an
// output only without it, and a refused run leaves the file as it was.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "test_support.h"
#include "tirpol/calibration/emissivity_extraction.h"
#include "tirpol/calibration/flir_image.h"
#include "tirpol/calibration/noise.h"
#include "tirpol/calibration/radiometric.h"
#include "tirpol/core/output_guard.h"

namespace tirpol::calibration {
namespace {

std::string contents(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// Runs `run` with the output on `input` (refused, forced or not), then on an existing file
// (refused unless forced, the file kept): the inputs hold no data, so a run that got past its
// guard would fail reading them with another error.
template <typename Options, typename Run>
void expect_guarded(const test::TempDir& dir, Options o, std::string Options::*output,
                    const std::string& input, Run run) {
    o.*output = input;
    o.force = true;
    EXPECT_THROW(run(o), OutputConflict) << input;
    o.*output = (dir / "existing.out").string();
    test::write_text(o.*output, "kept");
    o.force = false;
    EXPECT_THROW(run(o), OutputConflict) << input;
    EXPECT_EQ(contents(o.*output), "kept");
}

TEST(RunOutputGuard, CalibrationRunsRefuseToReplaceInputsOrUnforcedFilesBeforeReading) {
    const test::TempDir dir("run_output_guard");
    for (const char* name : {"stack.exr", "stokes.exr", "rois.yaml", "cal.exr", "raw.exr"})
        test::write_text(dir / name, "not data");
    const auto path = [&](const char* name) { return (dir / name).string(); };

    NoiseRunOptions noise;
    noise.stack = path("stack.exr");
    noise.calibration = path("cal.exr");
    noise.output = path("noise.json");
    expect_guarded(dir, noise, &NoiseRunOptions::nedt_map, path("cal.exr"),
                   [](const NoiseRunOptions& o) { run_noise_analysis(o); });
    noise.nedt_map.clear();
    expect_guarded(dir, noise, &NoiseRunOptions::output, path("stack.exr"),
                   [](const NoiseRunOptions& o) { run_noise_analysis(o); });

    EmissivityExtractionOptions extraction;
    extraction.input = path("stokes.exr");
    extraction.rois = path("rois.yaml");
    expect_guarded(dir, extraction, &EmissivityExtractionOptions::output, path("rois.yaml"),
                   [](const EmissivityExtractionOptions& o) { extract_emissivity(o); });

    FlirImageOptions flir;
    flir.image = path("raw.exr");
    expect_guarded(dir, flir, &FlirImageOptions::output, path("raw.exr"),
                   [](const FlirImageOptions& o) { flir_temperature_image(o); });

    TemperatureImageOptions temperature;
    temperature.image = path("raw.exr");
    temperature.calibration = path("cal.exr");
    expect_guarded(dir, temperature, &TemperatureImageOptions::output, path("cal.exr"),
                   [](const TemperatureImageOptions& o) { brightness_temperature_image(o); });
}

}  // namespace
}  // namespace tirpol::calibration
