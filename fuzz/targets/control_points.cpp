// Fuzz target: control-point files, each input read as both kinds: the pose estimation's CSV of
// world points and their pixels (calibration::read_control_points) and the report's YAML list of
// measured/simulated pixel pairs (report::load_control_points).
#include "fuzz_support.h"
#include "tirpol/calibration/geometric_calibration.h"
#include "tirpol/report/registration.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto csv = tirpol::fuzz::write_input("control_points.csv", data, size);
    tirpol::fuzz::expect_clean_rejection(
        [&] { (void)tirpol::calibration::read_control_points(csv); });
    const auto yaml = tirpol::fuzz::write_input("control_points.yaml", data, size);
    tirpol::fuzz::expect_clean_rejection([&] { (void)tirpol::report::load_control_points(yaml); });
    return 0;
}
