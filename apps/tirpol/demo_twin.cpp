// Demo step: the digital twin end to end (issue 9). The paper's nine panels under a clear night sky
// are rendered; the renderer's sensor model is the camera, served over GigE Vision on loopback;
// tirpol-stage-sim's APT engine on a pseudo-terminal is the polarizer mount; the capture loop of
// `tirpol acquire` records the sessions; calibration, reduction, emissivity extraction and the fit
// recover the flat black paint; a render with the fitted paint is compared with the measurement.

#include <cstdio>

#include "demo_steps.h"
#include "invocation.h"
#include "tirpol/twin/twin.h"

namespace tirpol::cli {

namespace {

void demo_twin(const std::filesystem::path& out_dir) {
    twin::TwinOptions options;
    options.out_dir = out_dir / "twin";
    options.tool_version = version_text();
    std::fputs(twin::twin_summary(twin::run_twin(options)).c_str(), stdout);
}

}  // namespace

TIRPOL_REGISTER_DEMO_STEP(800,
                          "Digital twin: render → GigE camera + pty stage → acquire → calibrate → "
                          "fit → re-render → compare",
                          demo_twin);

}  // namespace tirpol::cli
