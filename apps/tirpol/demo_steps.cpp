#include "demo_steps.h"

namespace tirpol::cli {

std::vector<DemoStep> demo_steps() {
    return {
        {"Radiometry: 8–14 µm band radiance, dL/dT and brightness-temperature round trip", demo_radiometry},
        {"Polarimetry: a wire-grid analyzer at 0/45/90/135° and Stokes reduction (eqs 14–16)", demo_analyzer},
    };
}

}  // namespace tirpol::cli
