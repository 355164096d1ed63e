// Fuzz target: sweep files (sweep::load_sweep), their points and each point's scene (point_config).
// The input is written next to links to the shipped scenes, materials and thermal scenes, so seeds
// name a real base scene as `scene: scenes/<file>.yaml` (`thermal/<file>.yaml` for a time axis) and
// every check against the base scene runs.
#include <filesystem>

#include "fuzz_support.h"
#include "tirpol/sweep/sweep_run.h"

namespace {
void link_config_folders() {
    static const bool linked = [] {
        for (const char* folder : {"scenes", "materials", "thermal"}) {
            const auto link = tirpol::fuzz::scratch_dir() / folder;
            std::error_code ignored;
            std::filesystem::remove(link, ignored);
            std::filesystem::create_directory_symlink(
                tirpol::fuzz::source_dir() / "config" / folder, link);
        }
        return true;
    }();
    (void)linked;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    link_config_folders();
    const auto path = tirpol::fuzz::write_input("sweep.yaml", data, size);
    tirpol::fuzz::expect_clean_rejection([&] {
        const auto spec = tirpol::sweep::load_sweep(path);
        const auto points = tirpol::sweep::sweep_points(spec);
        if (points.empty()) __builtin_trap();
        // The first and the last point: every axis at both ends of its values.
        (void)tirpol::sweep::point_config(spec, points.front());
        (void)tirpol::sweep::point_config(spec, points.back());
    });
    return 0;
}
