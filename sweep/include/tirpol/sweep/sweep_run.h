#pragma once
/// \file sweep_run.h
/// Running a sweep: every point rendered into OUT/points/<id>/ (stokes.exr with its PNG quicklooks,
/// pol<angle>.exr with a sensor model, statistics.json), each folder written under a temporary name
/// and renamed when complete, so a folder that exists is a finished point. OUT/manifest.json
/// records each point's parameters, seed, status and error; a failing point is recorded and the
/// sweep goes on.
///
/// Without mpirun the points are rendered one after the other, each with the renderer's threads.
/// Under `mpirun -np N` (Open MPI) rank 0 hands out point indices on request (dynamic: uneven point
/// costs balance themselves) and renders points itself on a second thread; every rank writes its
/// own points; rank 0 gathers the records, writes the manifest and the results. Images do not
/// depend on the number of ranks or threads: each point's seed comes from its index (point_seed)
/// and the renderer's output is thread-count independent (counter-based random numbers,
/// renderer.h).
///
/// Region statistics of one rendered sweep point: mean S0, S1, S2 (camera frame, band radiance
/// W/(m²·sr)), mean per-pixel DoLP and mean temperature over each region, with the Monte-Carlo
/// standard error of each mean, and contrasts mean(a) − mean(b) between regions.
///
/// Errors: the renderer's S*_var channels are the variance of each pixel's mean (renderer.h);
/// pixels are independent samples, so the error of a region mean is √(Σ var_i)/n. A pixel's DoLP
/// variance is propagated to first order from S0, S1, S2. The error of a contrast is √(σ_a² + σ_b²)
/// (disjoint regions are independent). NaN errors with one sample per pixel; NaN means for an empty
/// region.
///
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
#include "tirpol/core/image.h"
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

struct Estimate {
    double mean = 0.0;
    double error = 0.0;  ///< Monte-Carlo standard error of the mean
};

/// The quantities of one region or contrast, in the order of kQuantityNames.
struct QuantityEstimates {
    Estimate s0, s1, s2, dolp, temperature_k;
};
inline constexpr const char* kQuantityNames[] = {"S0", "S1", "S2", "DoLP", "temperature_k"};
const Estimate& quantity(const QuantityEstimates& q, std::size_t index);

struct RegionStatistics {
    std::string name;
    std::size_t pixel_count = 0;
    QuantityEstimates values;
};

struct ContrastStatistics {
    std::string name;
    QuantityEstimates values;  ///< mean(a) − mean(b)
};

struct PointStatistics {
    std::vector<RegionStatistics> regions;
    std::vector<ContrastStatistics> contrasts;
};

/// Statistics of a rendered image (renderer.h channels) over the sweep's regions; `objects` are the
/// scene's object names in object_id order. Throws tirpol::Error if a region's polygon leaves the
/// image.
PointStatistics point_statistics(const Image& image, const std::vector<std::string>& objects,
                                 const SweepSpec& spec);

/// The pixels of a region: 1 inside, 0 outside (row-major, the image's size).
std::vector<std::uint8_t> region_pixels(const Image& image, const std::vector<std::string>& objects,
                                        const RegionSpec& region);

struct RunOptions {
    int threads = 0;        ///< renderer threads per rank; 0: this machine's cores / ranks on it
    bool resume = false;    ///< continue a sweep in OUT: finished points are not rendered again
    bool progress = false;  ///< one line per finished point on stderr (rank 0)
};

/// What happened to one point.
struct PointRecord {
    SweepPoint point;
    std::string status =
        "pending";      ///< "rendered", "resumed" (finished by an earlier run), "failed", "pending"
    std::string error;  ///< why it failed
    int rank = 0;       ///< MPI rank that rendered it
    double seconds = 0.0;         ///< loading, thermal model, render and writing
    double render_seconds = 0.0;  ///< of which the renderer (the part that uses the threads)
    double wait_seconds = 0.0;    ///< time its rank waited for the assignment (scheduling overhead)
    std::optional<PointStatistics> statistics;
};

struct SweepSummary {
    bool is_root = true;  ///< false on MPI ranks other than 0 (they hold no records)
    int ranks = 1;
    int threads = 1;  ///< renderer threads per rank
    std::vector<PointRecord> points;
    std::size_t rendered = 0, resumed = 0, failed = 0;
    double wall_seconds = 0.0;
    std::vector<std::filesystem::path> outputs;  ///< manifest and results written by rank 0
};

/// Runs the sweep into `out_dir` (see above) and, on rank 0, writes the manifest and the results
/// (sweep_results.h). Throws tirpol::Error if `out_dir` holds a sweep and `resume` is off, or if it
/// holds a different sweep (other points or parameters) and `resume` is on.
SweepSummary run_sweep(const SweepSpec& spec, const std::filesystem::path& out_dir,
                       const RunOptions& options);

/// The outputs `run_sweep` claims in its folder (OutputGuard patterns): the manifest, the results,
/// the contact sheets and the points', plots', tiles' and animation folders.
const std::vector<std::string>& sweep_output_patterns();

/// What `tirpol sweep` prints on rank 0: points, ranks, threads, time, how many were rendered,
/// resumed and failed, the files written directly in `out_dir`, and each failed point with its
/// error. `sweep_name` names the sweep file.
std::string sweep_summary_text(const SweepSummary& summary, const std::string& sweep_name,
                               const std::filesystem::path& out_dir);

}  // namespace tirpol::sweep
