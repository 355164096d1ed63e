// Fuzz target: the calibrated camera's YAML files (core/camera_model.h), each input read as a
// camera model and as a camera pose. A model that reads must pass its own validation and survive a
// write → read round trip (calibration writes these files, simulation reads them back).
#include "fuzz_support.h"
#include "tirpol/core/camera_model.h"

namespace {
void trap_unless(bool ok) {
    if (!ok) __builtin_trap();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = tirpol::fuzz::write_input("camera.yaml", data, size);
    tirpol::fuzz::expect_clean_rejection([&] {
        const auto model = tirpol::read_camera_model(path);
        tirpol::validate_camera_model(model, path.string());
        const auto again_path = tirpol::fuzz::scratch_dir() / "camera_again.yaml";
        tirpol::write_camera_model(again_path, model);
        const auto again = tirpol::read_camera_model(again_path);
        trap_unless(again.width == model.width && again.height == model.height &&
                    again.distortion.size() == model.distortion.size());
        // What the renderer does with it: undistort a corner pixel (an iteration that must end).
        (void)model.undistort({0.0, 0.0});
    });
    tirpol::fuzz::expect_clean_rejection([&] { (void)tirpol::read_camera_pose(path); });
    return 0;
}
