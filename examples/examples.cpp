#include "examples.h"

#include <cstdio>
#include <exception>
#include <string>

#include "tirpol/core/error.h"

namespace tirpol::examples {

const std::vector<Example>& all_examples() {
    static const std::vector<Example> examples{
        {"radiometry",
         "Radiometry: 8–14 µm band radiance, dL/dT and brightness-temperature round trip",
         radiometry_example},
        {"analyzer",
         "Polarimetry: a wire-grid analyzer at 0/45/90/135° and Stokes reduction (eqs 14–16)",
         analyzer_example},
        {"materials",
         "Materials: polarized emissivity of the flat black paint (paper Fig. 1) and the material "
         "library",
         materials_example},
        {"thermal",
         "Thermal: SPA check and a day of ball-on-snow surface temperatures (1D slab model)",
         thermal_example},
        {"simulation",
         "Simulation: polarized LWIR renders of the paper's ball-on-snow and panel scenes",
         simulation_example},
        {"acquisition",
         "Acquisition: 0/45/90/135° session with a simulated K10CR1 (APT protocol on a pty) and "
         "camera",
         acquisition_example},
        {"calibration",
         "Calibration: blackbody radiometry, wire-grid removal, Stokes reduction, emissivity (eq "
         "17)",
         calibration_example},
        {"fitting",
         "Fitting: micro-facet parameters of the flat black paint from simulated polarized "
         "emissivity",
         fitting_example},
        {"twin",
         "Digital twin: render → GigE camera + pty stage → acquire → calibrate → fit → re-render → "
         "compare",
         twin_example},
    };
    return examples;
}

const Example& find_example(std::string_view name) {
    std::string known;
    for (const Example& example : all_examples()) {
        if (example.name == name) return example;
        known += (known.empty() ? "" : ", ") + example.name;
    }
    fail("no example called '{}' (the examples: {})", name, known);
}

int run_example_program(std::string_view name, int argc, char** argv) {
    if (argc > 2 || (argc == 2 && argv[1][0] == '-')) {
        std::fprintf(stderr, "usage: %s [OUT_DIR]   (default: example-output)\n", argv[0]);
        return 2;
    }
    try {
        const Example& example = find_example(name);
        const std::filesystem::path out_dir =
            std::filesystem::absolute(argc == 2 ? argv[1] : "example-output");
        std::printf("== %s\n", example.title.c_str());
        example.run(out_dir);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}

}  // namespace tirpol::examples
