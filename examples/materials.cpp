// Example: polarized emissivity of the paper's flat black paint target (its Fig. 1) from the
// material library, in the 8–14 µm band, as CSV and plot; plus the library's 10 µm emissivities.

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "examples.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/core/source_tree.h"
#include "tirpol/materials/emissivity.h"
#include "tirpol/materials/material.h"

namespace tirpol::examples {

namespace {
// config/materials of the source tree: searched upwards from the working directory and from the
// executable's directory (the demo runs from a build tree inside the repository).
std::filesystem::path find_material_library() { return find_config("materials"); }

}  // namespace

void materials_example(const std::filesystem::path& out_dir) {
    const auto library_dir = find_material_library();
    const auto library = materials::MaterialLibrary::load_directory(library_dir);
    const materials::Material& paint = library.get("flat_black_paint");
    const Band band(8.0, 14.0);
    const auto rows = materials::emissivity_curve(
        *paint.brdf, materials::parse_angles_deg("0:89:1"), band, 300.0);
    const auto dir = out_dir / "materials";
    std::filesystem::create_directories(dir);
    write_file_atomic(dir / "flat_black_paint_emissivity_8_14um.csv",
                      materials::emissivity_csv(rows));
    materials::write_emissivity_plot(dir / "flat_black_paint_emissivity_8_14um.png", rows,
                                     "flat black paint, 8-14 um band, 300 K (cf. paper Fig. 1)");
    for (double a : {0.0, 45.0, 60.0, 75.0, 85.0}) {
        const auto& r = rows[static_cast<std::size_t>(a)];
        std::printf("  flat black paint %2.0f°: e_S0 = %.4f, e_S1 = %+.4f, DoLP = %.4f\n", a,
                    r.e(0), r.e(1), r.dolp);
    }
    std::printf("  library (%zu materials from %s), e_S0 at 10 µm, 0° / 60° / 80°:\n",
                library.names().size(), library_dir.c_str());
    std::string summary = "material,model,e_s0_0deg,e_s0_60deg,e_s1_60deg,e_s0_80deg,e_s1_80deg\n";
    for (const auto& name : library.names()) {
        const auto& m = library.get(name);
        const auto r = materials::emissivity_curve(*m.brdf, {0.0, 60.0, 80.0}, 10.0);
        std::printf("    %-24s %.3f / %.3f / %.3f\n", name.c_str(), r[0].e(0), r[1].e(0),
                    r[2].e(0));
        summary += fmt::format("{},{},{:.5f},{:.5f},{:.5f},{:.5f},{:.5f}\n", name, m.brdf->model(),
                               r[0].e(0), r[1].e(0), r[1].e(1), r[2].e(0), r[2].e(1));
    }
    write_file_atomic(dir / "library_emissivity_10um.csv", summary);
    std::printf("  plot: %s\n", (dir / "flat_black_paint_emissivity_8_14um.png").c_str());
}

}  // namespace tirpol::examples
