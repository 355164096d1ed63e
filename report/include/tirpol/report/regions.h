#pragma once
/// \file regions.h
/// Regions of interest for the measured-vs-simulated comparison: named polygons in measured-image
/// pixel coordinates (x to the right, y down, origin top-left; a vertex (x, y) is the centre of
/// pixel column x, row y, and pixels on a polygon's edge belong to it). One region may be named the
/// background against which S1 contrast is computed, and one the flat region used to estimate the
/// measured noise when the measured image carries no uncertainty channels.
///
/// File format (YAML, keys checked, errors name file:line and the field):
/// ```yaml
/// background: sky_facing_bg      # optional: region for S1 contrast
/// noise_region: sky_facing_bg     # optional: flat region for the measured-noise estimate
/// regions:
///   - name: panel_black
///     polygon: [[120, 80], [200, 80], [200, 150], [120, 150]]
/// ```

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace tirpol {
class ConfigNode;
}

namespace tirpol::report {

/// A point in pixel coordinates (x = column, y = row, origin top-left).
struct PixelPoint {
    double x = 0.0;
    double y = 0.0;
};

/// A named polygon in measured-image pixel coordinates.
struct Region {
    std::string name;
    std::vector<PixelPoint> polygon;  ///< at least 3 vertices
    std::string location;             ///< "rois.yaml:7:5: regions[1]" for error messages
};

struct RegionSet {
    std::vector<Region> regions;
    std::string background;  ///< name of the S1-contrast background region; empty = none
    std::string
        noise_region;  ///< name of the flat region for the noise estimate; empty = background
};

/// Reads a regions YAML file (format above). Throws tirpol::Error naming file:line:field for a
/// syntax error, an unknown key, a polygon with fewer than 3 vertices or non-numeric coordinates,
/// a duplicate region name, or a background/noise_region that names no region.
RegionSet load_regions(const std::filesystem::path& path);
/// Same from an already parsed YAML root.
RegionSet parse_regions(const ConfigNode& root);

/// `set` as a regions YAML that load_regions reads back to the same set (names quoted, vertices
/// with 17 significant digits), so a report computed in memory can be repeated with `tirpol compare
/// --rois`.
std::string regions_yaml(const RegionSet& set);

/// The region rasterized on a width × height grid: 1 inside (edges included), 0 outside.
/// Throws tirpol::Error naming the region's location if a vertex lies outside the image
/// ([-0.5, width-0.5] × [-0.5, height-0.5]) or the polygon covers no pixel.
std::vector<std::uint8_t> region_mask(const Region& region, int width, int height);

/// A region covering the whole image, used when no regions are given.
Region whole_image_region(int width, int height);

}  // namespace tirpol::report
