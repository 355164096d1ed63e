// Example: the LWIR band the field camera sees, as a table a person can open.

#include "tirpol/core/radiometry.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "examples.h"
#include "tirpol/core/atomic_file.h"

namespace tirpol::examples {

void radiometry_example(const std::filesystem::path& out_dir) {
    const Band band(8.0, 14.0);
    std::ostringstream csv;
    csv << "temperature_k,radiance_w_m2_sr,radiance_dT_w_m2_sr_k,brightness_temperature_k,nedt_"
           "equivalent_radiance_80mK\n";
    double worst_round_trip_k = 0.0;
    for (int t = 230; t <= 350; t += 5) {
        const double l = band.radiance(t);
        const double tb = band.brightness_temperature(l);
        worst_round_trip_k = std::max(worst_round_trip_k, std::abs(tb - t));
        csv << t << ',' << l << ',' << band.radiance_dT(t) << ',' << tb << ','
            << 0.080 * band.radiance_dT(t) << '\n';
    }
    const auto path = out_dir / "radiometry" / "band_8_14um.csv";
    write_file_atomic(path, csv.str());
    std::printf("  L(300 K) = %.4f W/(m²·sr), dL/dT = %.5f W/(m²·sr·K) in 8–14 µm\n",
                band.radiance(300.0), band.radiance_dT(300.0));
    std::printf("  brightness-temperature round trip, 230–350 K: worst error %.2e K\n",
                worst_round_trip_k);
    std::printf("  table: %s\n", path.c_str());
}

}  // namespace tirpol::examples
