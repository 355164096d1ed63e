// `type: table`: band radiance against zenith angle from a CSV (e.g. converted from MODTRAN or
// libRadtran), turned into brightness temperatures over the band and interpolated linearly in
// zenith angle; ε = 1.

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "csv_columns.h"
#include "sky_model.h"
#include "tirpol/core/error.h"
#include "tirpol/core/geometry.h"

namespace tirpol::simulation {

namespace {

class TableSky final : public SkyModel {
public:
    TableSky(std::vector<double> zenith_deg, std::vector<double> brightness_k)
        : m_zenith_deg(std::move(zenith_deg)), m_brightness_k(std::move(brightness_k)) {}

    double emissivity(double) const override { return 1.0; }
    double temperature_k(double cos_zenith) const override {
        const double z = rad_to_deg(std::acos(std::clamp(cos_zenith, 0.0, 1.0)));
        if (z <= m_zenith_deg.front()) return m_brightness_k.front();
        if (z >= m_zenith_deg.back()) return m_brightness_k.back();
        const auto it = std::upper_bound(m_zenith_deg.begin(), m_zenith_deg.end(), z);
        const auto i = static_cast<std::size_t>(it - m_zenith_deg.begin());
        const double t = (z - m_zenith_deg[i - 1]) / (m_zenith_deg[i] - m_zenith_deg[i - 1]);
        return (1.0 - t) * m_brightness_k[i - 1] + t * m_brightness_k[i];
    }

private:
    std::vector<double> m_zenith_deg, m_brightness_k;
};

}  // namespace

Sky Sky::table(std::vector<double> zenith_deg, std::vector<double> band_radiance,
               const Band& band) {
    if (zenith_deg.size() != band_radiance.size() || zenith_deg.empty())
        fail("sky table: need matching, non-empty zenith and radiance columns");
    std::vector<double> brightness_k;
    for (std::size_t i = 0; i < zenith_deg.size(); ++i) {
        if (i > 0 && !(zenith_deg[i] > zenith_deg[i - 1]))
            fail("sky table: zenith_deg must increase strictly (row {}: {} after {})", i + 1,
                 zenith_deg[i], zenith_deg[i - 1]);
        if (!(band_radiance[i] > 0.0))
            fail("sky table: radiance must be positive (row {}: {})", i + 1, band_radiance[i]);
        brightness_k.push_back(band.brightness_temperature(band_radiance[i]));
    }
    return Sky(std::make_shared<const TableSky>(std::move(zenith_deg), std::move(brightness_k)));
}

namespace skies {

Sky table_from_config(const ConfigNode& node, const Band& band) {
    node.check_keys({"type", "file"});
    const auto path = node.resolve_path(node.get<std::string>("file"));
    if (!std::filesystem::exists(path))
        node.at("file").fail("sky table file not found: " + path.string());
    auto cols = read_csv_columns(path, {"zenith_deg", "radiance_w_m2_sr"});
    return Sky::table(std::move(cols[0]), std::move(cols[1]), band);
}

}  // namespace skies

}  // namespace tirpol::simulation
