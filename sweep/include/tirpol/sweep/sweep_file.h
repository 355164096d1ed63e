#pragma once
/// \file sweep_file.h
/// The sweep file (YAML, docs/sweep.md): a base scene, optional sensor model, overrides for every
/// point, and axes of values to vary, combined as a grid (every combination) or a list (the i-th
/// values together). Each point's scene is the base scene's YAML with the point's overrides
/// (ConfigNode::with_value), read by the one scene loader. Errors name the sweep file, line and
/// field.
///
/// Parameter names:
/// - a path in the scene file: `time`, `camera.position`, `band`,
/// `objects[ball].transform.translate`,
///   `sampling.spp`, … (keys joined by '.', list elements by `[index]` or `[name]`);
/// - `sensor.<path>` in the sensor-model file (`sensor.counts.nedt_k`);
/// - `materials.<name>.<path>` in the library material `<name>`
/// (`materials.snow.parameters.sigma`): every
///   object whose `material:` is that name gets the modified material inline.
/// Every step of a path must exist in the base files (an unknown name gets a "did you mean").

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "tirpol/core/config.h"
#include "tirpol/report/regions.h"

namespace tirpol::sweep {

/// One axis: a parameter and the values it takes, in order.
struct Axis {
    std::string parameter;
    std::vector<ConfigNode> values;
    std::vector<std::string>
        labels;  ///< each value as compact YAML-like text (manifest, tables, plots)
    /// Each value as a number for plots: the value itself if numeric, hours since the first value
    /// for `time`, else the value's position on the axis.
    std::vector<double> coordinates;
    std::string
        coordinate_label;  ///< x-axis title for plots, e.g. "time [h since 2026-01-16T00:00]"
};

/// A named group of pixels of a rendered point: an object's pixels (object_id), optionally only
/// those within angular sectors around the object's pixel centroid (0° = image right, 90° = image
/// top, as the Stokes reference), and/or a polygon in pixel coordinates.
struct RegionSpec {
    std::string name;
    std::string object;  ///< empty: any pixel
    std::vector<std::pair<double, double>>
        sectors_deg;  ///< [from, to] counter-clockwise; empty: all
    std::optional<report::Region> polygon;
    std::string location;
};

/// mean(a) − mean(b) of every quantity, with the Monte-Carlo error of the difference.
struct ContrastSpec {
    std::string name, a, b;
};

enum class Combine { Grid, List };

struct SweepSpec {
    std::filesystem::path file;
    ConfigNode scene;                  ///< the base scene
    std::optional<ConfigNode> sensor;  ///< the base sensor model (polarizer images per point)
    std::vector<std::pair<std::string, ConfigNode>>
        fixed;  ///< `set:` overrides applied to every point
    std::vector<Axis> axes;
    Combine combine = Combine::Grid;
    std::uint64_t seed = 1;
    std::vector<RegionSpec> regions;  ///< default: one region per scene object
    std::vector<ContrastSpec> contrasts;
};

/// Reads and checks a sweep file: keys, every parameter against the base files, axes non-empty (and
/// of equal length for `combine: list`), regions naming objects of the base scene, contrasts naming
/// regions.
SweepSpec load_sweep(const std::filesystem::path& path);

/// One point: which value of each axis, its seed and its folder name.
struct SweepPoint {
    std::size_t index = 0;
    std::vector<std::size_t> value_index;  ///< per axis
    std::uint64_t seed = 0;
    std::string id;  ///< "p0007": zero-padded index, the folder OUT/points/<id>
};

/// The points in order: for a grid the first axis varies slowest.
std::vector<SweepPoint> sweep_points(const SweepSpec& spec);

/// Seed of point `index`: SplitMix64 of the sweep seed and the index (Steele, Lea & Flood, "Fast
/// splittable pseudorandom number generators", OOPSLA 2014), so it depends on nothing but the two,
/// whichever rank renders the point; below 2^63 so it fits every signed field.
std::uint64_t point_seed(std::uint64_t sweep_seed, std::size_t index);

/// The point's scene and sensor files: base + `set:` + the point's axis values.
struct PointConfig {
    ConfigNode scene;
    std::optional<ConfigNode> sensor;
};
PointConfig point_config(const SweepSpec& spec, const SweepPoint& point);

}  // namespace tirpol::sweep
