// Example: the digital twin end to end. The paper's nine panels under a clear night sky
// are rendered; the renderer's sensor model is the camera, served over GigE Vision on loopback;
// tirpol-stage-sim's APT engine on a pseudo-terminal is the polarizer mount; the capture loop of
// `tirpol acquire` records the sessions; calibration, reduction, emissivity extraction and the fit
// recover the flat black paint; a render with the fitted paint is compared with the measurement.

#include "tirpol/twin/twin.h"

#include <cstdio>
#include <string>

#include "examples.h"

namespace tirpol::examples {

void twin_example(const std::filesystem::path& out_dir) {
    twin::TwinOptions options;
    options.out_dir = out_dir / "twin";
    options.tool_version = std::string("tirpol ") + TIRPOL_VERSION;
    std::fputs(twin::twin_summary(twin::run_twin(options)).c_str(), stdout);
}

}  // namespace tirpol::examples
