#pragma once
// The examples: the pipeline step by step, one program each (tirpol-example-<name> [OUT_DIR]), each
// using only the libraries' public headers. `tirpol demo` runs them all in pipeline order
// (docs/demo.md). Each writes under <OUT_DIR>/<name>/ and prints what it recovered against the
// truth it simulated.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace tirpol::examples {

/// One example: the folder it writes under the output folder (also its program's suffix), a
/// one-line title and the function that runs it.
struct Example {
    std::string name;
    std::string title;
    void (*run)(const std::filesystem::path& out_dir);
};

/// Every example, in pipeline order.
const std::vector<Example>& all_examples();

/// The example called `name`; a tirpol::Error listing the known names when there is none.
const Example& find_example(std::string_view name);

/// main() of an example program: `<program> [OUT_DIR]` (default "example-output") runs the example
/// `name` into OUT_DIR. Returns the exit status: 0, 1 after printing the error, 2 on bad usage.
int run_example_program(std::string_view name, int argc, char** argv);

/// The 8–14 µm band: radiance, dL/dT and the brightness-temperature round trip (radiometry/).
void radiometry_example(const std::filesystem::path& out_dir);
/// A Stokes test pattern through the paper's wire grid, reduced with eqs 14–16 (analyzer/).
void analyzer_example(const std::filesystem::path& out_dir);
/// The flat black paint's polarized emissivity and the material library (materials/).
void materials_example(const std::filesystem::path& out_dir);
/// The SPA check and a day of ball-on-snow surface temperatures (thermal/).
void thermal_example(const std::filesystem::path& out_dir);
/// Polarized renders of the ball-on-snow and nine-panel scenes (simulation/).
void simulation_example(const std::filesystem::path& out_dir);
/// A 0/45/90/135° session from a simulated K10CR1 on a pty and a simulated camera (acquisition/).
void acquisition_example(const std::filesystem::path& out_dir);
/// Simulated sessions with known truth calibrated, reduced, and eq 17 emissivity (calibration/).
void calibration_example(const std::filesystem::path& out_dir);
/// The micro-facet parameters of the flat black paint fitted to simulated emissivity (fitting/).
void fitting_example(const std::filesystem::path& out_dir);
/// The digital twin end to end: render, capture, calibrate, fit, re-render, compare (twin/).
void twin_example(const std::filesystem::path& out_dir);

}  // namespace tirpol::examples
