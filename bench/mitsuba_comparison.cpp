// tirpol against Mitsuba 3 at equal noise (docs/simulation.md "Speed"; part of
// tirpol_simulation_bench):
//  - ReflectionEqualNoise: config/scenes/reflection_compare.yaml (nothing emits: the sky reflected
//    by a smooth sphere and a rough plane), noise over every surface pixel.
//  - EmissionEqualNoise: config/scenes/emission_compare.yaml (a closed room of Lambertian walls at
//    six temperatures and two rough spheres at 1 K: all radiance is the walls' emission, all
//    polarization that emission seen in reflection), noise over the spheres' pixels.
// Each: the time to a relative linear-polarization noise of 1 %, measured from two renders with
// different seeds, each renderer run at doubling spp from 16 until its noise is ≤ 1 % and its time
// interpolated in log-log between the two runs that bracket 1 % (no 1/√N extrapolation); the same
// for Mitsuba 3 with each of its samplers (independent, stratified, multijitter, orthogonal,
// ldsampler; TIRPOL_MITSUBA_SAMPLERS picks some) when TIRPOL_MITSUBA names its `mitsuba`
// executable (built scalar_mono_polarized), else skipped, after checking per object that both
// renderers' mean Stokes agree (else no ratio); the ratio against the best sampler is printed.
//  - EmissionPaths (figures): how emission_compare's radiance arrives (own emission, one
//    reflection, more), from renders with the reflections capped at 0 and 1.

#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "stokes_render_pair.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/geometry.h"
#include "tirpol/core/source_tree.h"
#include "tirpol/core/stokes.h"
#include "tirpol/simulation/renderer.h"
#include "tirpol/simulation/scene.h"

namespace {

using namespace tirpol;
using namespace tirpol::simulation;
using bench::kStokesChannels;
using bench::noise_mask;
using bench::relative_linear_noise;
using bench::RenderPair;

/// Mean Stokes of a render pair's average over a region, with standard errors from the pair's
/// per-pixel differences: Var((a + b)/2) = Var(a − b)/4 for independent seeds.
struct RegionStokes {
    std::size_t pixels = 0;
    double s0 = 0.0, s0_se = 0.0;               ///< mean S0, W/(m²·sr)
    std::array<double, 3> ratio{}, ratio_se{};  ///< ΣS1/ΣS0, ΣS2/ΣS0, ΣS3/ΣS0 (delta method)
};

RegionStokes region_stokes(const RenderPair& p, const std::vector<bool>& region) {
    RegionStokes r;
    std::array<double, 4> sum{};
    for (std::size_t i = 0; i < region.size(); ++i) {
        if (!region[i]) continue;
        for (std::size_t c = 0; c < 4; ++c)
            sum[c] +=
                0.5 * (p.a.channel(kStokesChannels[c])[i] + p.b.channel(kStokesChannels[c])[i]);
        ++r.pixels;
    }
    for (std::size_t c = 1; c < 4; ++c) r.ratio[c - 1] = sum[c] / sum[0];
    std::array<double, 4> var{};  // of the region sums
    for (std::size_t i = 0; i < region.size(); ++i) {
        if (!region[i]) continue;
        const double d0 = p.a.channel("S0")[i] - p.b.channel("S0")[i];
        var[0] += 0.25 * d0 * d0;
        for (std::size_t c = 1; c < 4; ++c) {
            const double d = p.a.channel(kStokesChannels[c])[i] -
                             p.b.channel(kStokesChannels[c])[i] - r.ratio[c - 1] * d0;
            var[c] += 0.25 * d * d;
        }
    }
    const auto n = static_cast<double>(r.pixels);
    r.s0 = sum[0] / n;
    r.s0_se = std::sqrt(var[0]) / n;
    for (std::size_t c = 1; c < 4; ++c) r.ratio_se[c - 1] = std::sqrt(var[c]) / sum[0];
    return r;
}

/// Worst disagreement between the two renderers over all regions.
struct Agreement {
    double max_abs_z = 0.0;  ///< of S0, S1/S0, S2/S0, S3/S0, difference over its standard error
    double max_relative_ds0 = 0.0;      ///< |ΔS0| / S0
    double max_ratio_difference = 0.0;  ///< |Δ(Sk/S0)|, k = 1..3
};

/// Difference over its standard error; 0 where both renderers give the region no noise at all
/// (a Lambertian wall's S1/S0 is exactly 0 in both) and the values are equal.
double z_score(double difference, double se_a, double se_b) {
    const double se = std::hypot(se_a, se_b);
    if (se > 0.0) return difference / se;
    return difference == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
}

/// Prints, per object and image half, the means of both renderers with the z of their difference.
Agreement check_agreement(const Scene& scene, const RenderPair& tirpol, const RenderPair& mitsuba) {
    const Image& ids = tirpol.a;  // object hit by each pixel's centre ray (−1: sky)
    Agreement worst;
    std::printf(
        "Agreement per region: tirpol | Mitsuba (in tirpol's frame) (z = difference / its standard "
        "error)\n");
    for (std::size_t object = 0; object < scene.objects.size(); ++object)
        for (const bool right : {false, true}) {
            std::vector<bool> region(ids.pixel_count());
            for (int y = 0; y < ids.height(); ++y)
                for (int x = 0; x < ids.width(); ++x) {
                    const std::size_t i = ids.index(x, y);
                    region[i] = ids.channel("object_id")[i] == static_cast<float>(object) &&
                                (2 * x >= ids.width()) == right;
                }
            const RegionStokes t = region_stokes(tirpol, region),
                               m = region_stokes(mitsuba, region);
            if (t.pixels == 0) continue;
            const double z0 = z_score(m.s0 - t.s0, m.s0_se, t.s0_se);
            std::printf("  %-8s %-5s %6zu px  S0 %.4f | %.4f (z %+.1f)",
                        scene.objects[object].name.c_str(), right ? "right" : "left", t.pixels,
                        t.s0, m.s0, z0);
            worst.max_abs_z = std::max(worst.max_abs_z, std::abs(z0));
            worst.max_relative_ds0 = std::max(worst.max_relative_ds0, std::abs(m.s0 - t.s0) / t.s0);
            for (std::size_t k = 0; k < 3; ++k) {
                const double d = m.ratio[k] - t.ratio[k],
                             z = z_score(d, m.ratio_se[k], t.ratio_se[k]);
                std::printf("  S%zu/S0 %+.4f | %+.4f (z %+.1f)", k + 1, t.ratio[k], m.ratio[k], z);
                worst.max_abs_z = std::max(worst.max_abs_z, std::abs(z));
                worst.max_ratio_difference = std::max(worst.max_ratio_difference, std::abs(d));
            }
            std::printf("\n");
        }
    return worst;
}

/// Writes Mitsuba 3's version of reflection_compare.yaml and its envmap of the scene's sky.
/// Mitsuba's envmap is a lat-long image, y-up (rotated here to tirpol's z-up), whose row r lies at
/// zenith angle π·r/(rows − 1) (emitters/envmap.cpp: rows are samples from pole to pole, not pixel
/// centres). `sampler` is the Mitsuba sampler plugin (independent, stratified, multijitter,
/// orthogonal, ldsampler); Mitsuba rounds sample counts that a sampler cannot take (stratified: a
/// square; orthogonal: a prime squared), which does not matter here since times are interpolated
/// against the measured noise.
std::filesystem::path write_reflection_scene(const std::filesystem::path& dir, const Scene& scene,
                                             const std::string& sampler) {
    const int w = 256, h = 129;
    Image env(w, h);
    for (const char* c : {"R", "G", "B"}) env.add_channel(c);
    for (int y = 0; y < h; ++y) {
        const double theta = kPi * y / (h - 1);
        // Sky radiance at this zenith angle as tirpol sees it, integrated over the band.
        const Vec3 d(std::sin(theta), 0.0, std::cos(theta));
        double l = 0.0;
        for (const auto& node : scene.band.nodes())
            l += node.weight_um * scene.sky.spectral_radiance(node.wavelength_um, d);
        for (int x = 0; x < w; ++x)
            for (const char* c : {"R", "G", "B"})
                env.channel(c)[env.index(x, y)] = static_cast<float>(l);
    }
    write_exr(dir / "sky.exr", env);
    std::ofstream xml(dir / "scene.xml");
    xml << R"(<scene version="3.0.0">
  <default name="spp" value="16"/>
  <default name="seed" value="0"/>
  <integrator type="stokes"><integrator type="path"><integer name="max_depth" value="9"/></integrator></integrator>
  <sensor type="perspective">
    <float name="fov" value="40"/><string name="fov_axis" value="x"/>
    <transform name="to_world"><lookat origin="0, -5, 1.5" target="0, 0, 0.6" up="0, 0, 1"/></transform>
    <sampler type=")"
        << sampler
        << R"("><integer name="sample_count" value="$spp"/><integer name="seed" value="$seed"/></sampler>
    <film type="hdrfilm"><integer name="width" value="320"/><integer name="height" value="256"/>
      <string name="component_format" value="float32"/><rfilter type="box"/></film>
  </sensor>
  <emitter type="envmap"><string name="filename" value="sky.exr"/>
    <transform name="to_world"><rotate x="1" angle="90"/></transform></emitter>
  <shape type="rectangle">
    <transform name="to_world"><scale value="10"/></transform>
    <bsdf type="roughconductor"><string name="distribution" value="beckmann"/><float name="alpha" value="0.28284"/>
      <spectrum name="eta" value="1.5"/><spectrum name="k" value="0.05"/></bsdf>
  </shape>
  <shape type="sphere"><point name="center" value="0, 0, 0.6"/><float name="radius" value="0.6"/>
    <bsdf type="conductor"><spectrum name="eta" value="1.5"/><spectrum name="k" value="0.05"/></bsdf>
  </shape>
</scene>
)";
    return dir / "scene.xml";
}

/// A wall of emission_compare.yaml as a Mitsuba rectangle: centre, half extents along two axes and
/// the normal into the room, a × b = n (Mitsuba's area emitter and diffuse BSDF are one-sided, so
/// the front must face the room; tirpol's planes are two-sided).
struct MitsubaWall {
    Vec3 centre, half_a, half_b, inward;
};

/// The room's walls, as in config/scenes/emission_compare.yaml (x −2…2, y −2.5…2.5, z 0…3 m, each
/// 1 cm larger on every side).
const std::map<std::string, MitsubaWall> kEmissionWalls = {
    {"floor", {{0, 0, 0}, {2.01, 0, 0}, {0, 2.51, 0}, {0, 0, 1}}},
    {"ceiling", {{0, 0, 3}, {0, 2.51, 0}, {2.01, 0, 0}, {0, 0, -1}}},
    {"west", {{-2, 0, 1.5}, {0, 2.51, 0}, {0, 0, 1.51}, {1, 0, 0}}},
    {"east", {{2, 0, 1.5}, {0, 0, 1.51}, {0, 2.51, 0}, {-1, 0, 0}}},
    {"north", {{0, 2.5, 1.5}, {2.01, 0, 0}, {0, 0, 1.51}, {0, -1, 0}}},
    {"south", {{0, -2.5, 1.5}, {0, 0, 1.51}, {2.01, 0, 0}, {0, 1, 0}}},
};

/// The spheres of emission_compare.yaml as Mitsuba shapes: centre, radius and a `roughconductor`
/// of the same complex index, Beckmann α = √2·σ (tirpol's Gaussian slopes σ per axis).
const std::map<std::string, std::string> kEmissionSpheres = {
    {"paint",
     R"(<shape type="sphere"><point name="center" value="-0.75, 0.6, 0.6"/><float name="radius" value="0.6"/>
    <bsdf type="roughconductor"><string name="distribution" value="beckmann"/><float name="alpha" value="0.28284"/>
      <spectrum name="eta" value="1.5"/><spectrum name="k" value="0.05"/></bsdf></shape>)"},
    {"metal",
     R"(<shape type="sphere"><point name="center" value="0.75, 0.6, 0.6"/><float name="radius" value="0.6"/>
    <bsdf type="roughconductor"><string name="distribution" value="beckmann"/><float name="alpha" value="0.141421"/>
      <spectrum name="eta" value="2"/><spectrum name="k" value="3"/></bsdf></shape>)"},
};

/// A grey Lambertian's reflectance ρ (its emissivity is 1 − ρ): Mitsuba's mono emitter and BSDF
/// take one value for the whole band, so one that varies over the band is refused.
double grey_reflectance(const SceneMaterial& material, const Band& band) {
    const auto at = [&](double wavelength_um) {
        for (const auto& p : material.brdf->parameters(wavelength_um))
            if (p.name == "reflectance") return p.value;
        throw Error("material " + material.name + ": model " + material.brdf->model() +
                    " has no `reflectance`; expected a lambertian wall");
    };
    const double lo = at(band.lo_um()), hi = at(band.hi_um()),
                 mid = at(0.5 * (band.lo_um() + band.hi_um()));
    if (lo != hi || lo != mid)
        throw Error("material " + material.name + ": reflectance varies over the band (" +
                    std::to_string(lo) + " … " + std::to_string(hi) +
                    "); Mitsuba's mono variant needs a grey wall");
    return lo;
}

/// Writes Mitsuba 3's version of emission_compare.yaml. Each wall is an `area` emitter of radiance
/// (1 − ρ)·L_band(T) — tirpol's Kirchhoff emission of a Lambertian integrated over the scene's band
/// (core Band::radiance, the same integral tirpol's spectral grid sums) — with a `diffuse` BSDF of
/// albedo ρ; ρ and T are read from the loaded scene. The spheres are at 1 K in tirpol (no emission
/// in the band), as Mitsuba's BSDFs do not emit. The camera is the scene's (pinhole, centred, no
/// distortion: anything else is refused). Paths are unbounded in both (Mitsuba max_depth −1,
/// Russian roulette from depth 5; tirpol's roulette from the third hit).
std::filesystem::path write_emission_scene(const std::filesystem::path& dir, const Scene& scene,
                                           const std::string& sampler) {
    const PinholeCamera& camera = scene.camera;
    const CameraIntrinsics& k = camera.intrinsics();
    if (k.fx != k.fy || k.cx != 0.5 * camera.width() || k.cy != 0.5 * camera.height() ||
        k.k1 != 0.0 || k.k2 != 0.0 || k.p1 != 0.0 || k.p2 != 0.0 || k.k3 != 0.0)
        throw Error(scene.file.string() +
                    ": the Mitsuba export needs a centred pinhole camera with square pixels and no "
                    "distortion");
    const double fov_deg = rad_to_deg(2.0 * std::atan(0.5 * camera.width() / k.fx));
    const Vec3 origin = camera.position(), target = origin + camera.world_from_camera().col(2),
               up = -camera.world_from_camera().col(1);
    const auto vec = [](const Vec3& v) {
        char text[96];
        std::snprintf(text, sizeof text, "%.9g, %.9g, %.9g", v.x(), v.y(), v.z());
        return std::string(text);
    };
    std::ofstream xml(dir / "scene.xml");
    char line[512];
    std::snprintf(line, sizeof line, R"(<scene version="3.0.0">
  <default name="spp" value="16"/>
  <default name="seed" value="0"/>
  <integrator type="stokes"><integrator type="path"><integer name="max_depth" value="-1"/></integrator></integrator>
  <sensor type="perspective">
    <float name="fov" value="%.9g"/><string name="fov_axis" value="x"/>
)",
                  fov_deg);
    xml << line << R"(    <transform name="to_world"><lookat origin=")" << vec(origin)
        << R"(" target=")" << vec(target) << R"(" up=")" << vec(up) << R"("/></transform>
    <sampler type=")"
        << sampler
        << R"("><integer name="sample_count" value="$spp"/><integer name="seed" value="$seed"/></sampler>
    <film type="hdrfilm"><integer name="width" value=")"
        << camera.width() << R"("/><integer name="height" value=")" << camera.height() << R"("/>
      <string name="component_format" value="float32"/><rfilter type="box"/></film>
  </sensor>
)";
    for (const SceneObject& object : scene.objects) {
        if (const auto sphere = kEmissionSpheres.find(object.name);
            sphere != kEmissionSpheres.end()) {
            if (object.temperature.max_k() > 1.0)
                throw Error(scene.file.string() + ": object " + object.name +
                            " must be at ≤ 1 K (Mitsuba's BSDFs do not emit)");
            xml << "  " << sphere->second << "\n";
            continue;
        }
        const auto wall = kEmissionWalls.find(object.name);
        if (wall == kEmissionWalls.end() || !object.temperature.is_constant())
            throw Error(scene.file.string() + ": object " + object.name +
                        " is not one of the walls or spheres the Mitsuba export knows (floor, "
                        "ceiling, west, east, north, south at one temperature; paint, metal)");
        const double reflectance = grey_reflectance(scene.materials[object.material], scene.band);
        const double radiance =
            (1.0 - reflectance) * scene.band.radiance(object.temperature.min_k());
        const MitsubaWall& w = wall->second;
        std::snprintf(
            line, sizeof line,
            R"(  <shape type="rectangle"><transform name="to_world"><matrix value="%g %g %g %g  %g %g %g %g  %g %g %g %g  0 0 0 1"/></transform>
    <bsdf type="diffuse"><spectrum name="reflectance" value="%.9g"/></bsdf>
    <emitter type="area"><spectrum name="radiance" value="%.9g"/></emitter></shape>
)",
            w.half_a.x(), w.half_b.x(), w.inward.x(), w.centre.x(), w.half_a.y(), w.half_b.y(),
            w.inward.y(), w.centre.y(), w.half_a.z(), w.half_b.z(), w.inward.z(), w.centre.z(),
            reflectance, radiance);
        xml << line;
    }
    xml << "</scene>\n";
    return dir / "scene.xml";
}

/// One renderer's runs at doubling spp until the relative noise falls to the target.
struct NoiseRun {
    int spp = 0;
    double noise = 0.0, seconds = 0.0, cpu_seconds = 0.0;
};

/// Seconds (wall, CPU) to `target` noise, interpolated in log-log between the two runs that bracket
/// it (the last run is at or below the target, the one before above it); no 1/√N extrapolation.
std::pair<double, double> bracketed_seconds(const std::vector<NoiseRun>& runs, double target) {
    if (runs.size() < 2 || runs.back().noise > target || runs[runs.size() - 2].noise <= target)
        throw Error("no pair of runs brackets the target noise");
    const NoiseRun &lo = runs[runs.size() - 2], &hi = runs.back();
    const double f = std::log(target / lo.noise) / std::log(hi.noise / lo.noise);
    const auto interpolate = [f](double a, double b) {
        return std::exp(std::log(a) + f * (std::log(b) - std::log(a)));
    };
    return {interpolate(lo.seconds, hi.seconds), interpolate(lo.cpu_seconds, hi.cpu_seconds)};
}

/// Seconds of Mitsuba's "Rendering finished. (took 2.3456s)" log line (util::time_string's
/// ms/s/m/h).
double mitsuba_render_seconds(const std::filesystem::path& log_path) {
    std::ifstream log(log_path);
    const std::string key = "Rendering finished. (took ";
    for (std::string line; std::getline(log, line);) {
        const auto at = line.find(key);
        if (at == std::string::npos) continue;
        std::size_t end = 0;
        const std::string rest = line.substr(at + key.size());
        const double value = std::stod(rest, &end);
        const std::string unit = rest.substr(end, rest.find(')') - end);
        const double scale = unit == "ms"  ? 1e-3
                             : unit == "s" ? 1.0
                             : unit == "m" ? 60.0
                             : unit == "h" ? 3600.0
                                           : -1.0;
        if (scale > 0.0) return value * scale;
    }
    throw Error(log_path.string() +
                ": no \"Rendering finished. (took …)\" line with a time in ms, s, m or h");
}

/// The sample count Mitsuba rendered for `requested`: its samplers round counts they cannot take
/// up (stratified: a square; multijitter: a near-square product; orthogonal: a prime squared;
/// ldsampler: a power of four) and log it at warning level as "rounding to N" or "rounded up to N"
/// (samplers/*.cpp, v3.8.0); without such a line the count is the one requested.
int mitsuba_sample_count(const std::filesystem::path& log_path, int requested) {
    std::ifstream log(log_path);
    for (std::string line; std::getline(log, line);)
        for (const std::string key : {"rounding to ", "rounded up to "}) {
            const auto at = line.find(key);
            if (at == std::string::npos) continue;
            const int count = std::atoi(line.c_str() + at + key.size());
            if (count < requested)
                throw Error(log_path.string() + ": Mitsuba's sample count " +
                            std::to_string(count) + " is below the " + std::to_string(requested) +
                            " requested; expected it rounded up: \"" + line + "\"");
            return count;
        }
    return requested;
}

/// Mitsuba's Stokes AOVs (stokes integrator, mono: S0.R = S0.G = S0.B), re-expressed per pixel from
/// Mitsuba's frame (x = ray.d × camera-up) to tirpol's (camera-right projected onto the wavefront),
/// both for the pixel's centre ray.
Image in_tirpol_frame(const Image& mitsuba, const PinholeCamera& camera) {
    Image out(mitsuba.width(), mitsuba.height());
    for (const auto& c : kStokesChannels) out.set_channel(c, mitsuba.channel(c + ".R"));
    const Vec3 up = -camera.world_from_camera().col(1);  // camera axes: x right, y down, z forward
    for (int y = 0; y < out.height(); ++y)
        for (int x = 0; x < out.width(); ++x) {
            const Vec3 d = camera.ray_direction(x + 0.5, y + 0.5);
            const StokesFrame from{-d, d.cross(up).normalized()};
            const std::size_t i = out.index(x, y);
            float &s1 = out.channel("S1")[i], &s2 = out.channel("S2")[i];
            const StokesVector s =
                change_frame(StokesVector(out.channel("S0")[i], s1, s2, out.channel("S3")[i]), from,
                             camera.image_frame(d));
            s1 = static_cast<float>(s[1]);
            s2 = static_cast<float>(s[2]);
        }
    return out;
}

/// CPU seconds (user + system) of the waited-for child processes so far.
double children_cpu_seconds() {
    rusage usage{};
    getrusage(RUSAGE_CHILDREN, &usage);
    const auto seconds = [](const timeval& t) {
        return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
    };
    return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

/// Two Mitsuba 3 renders of `xml` (seeds 1 and 2) with `threads` threads. seconds is Mitsuba's own
/// render time (its log), without its start-up and scene loading, as tirpol's is without its own;
/// cpu_seconds is the whole process's (start-up, ~0.05 s, included); samples_per_pixel is the count
/// its sampler rendered.
RenderPair render_mitsuba(const std::string& executable, const std::filesystem::path& xml, int spp,
                          int threads, const PinholeCamera& camera) {
    RenderPair pair;
    for (const int seed : {1, 2}) {
        const auto out = xml.parent_path() / ("out" + std::to_string(seed) + ".exr");
        const auto log = xml.parent_path() / ("out" + std::to_string(seed) + ".log");
        const std::string command = "'" + executable + "' -m scalar_mono_polarized -t " +
                                    std::to_string(threads) + " -D spp=" + std::to_string(spp) +
                                    " -D seed=" + std::to_string(seed) + " -o '" + out.string() +
                                    "' '" + xml.string() + "' > '" + log.string() + "' 2>&1";
        const double cpu_before = children_cpu_seconds();
        if (std::system(command.c_str()) != 0)
            throw Error("Mitsuba 3 failed (log: " + log.string() + "): " + command);
        pair.cpu_seconds += 0.5 * (children_cpu_seconds() - cpu_before);
        pair.seconds += 0.5 * mitsuba_render_seconds(log);
        pair.samples_per_pixel = mitsuba_sample_count(log, spp);
        (seed == 1 ? pair.a : pair.b) = in_tirpol_frame(read_exr(out), camera);
    }
    return pair;
}

constexpr double kTargetNoise = 0.01;  // relative S1/S2 noise both renderers are run to
constexpr int kMaxBracketSpp = 1 << 14;

const std::vector<std::string> kMitsubaSamplers = {"independent", "stratified", "multijitter",
                                                   "orthogonal", "ldsampler"};

/// The Mitsuba samplers to compare: TIRPOL_MITSUBA_SAMPLERS, comma-separated names from
/// kMitsubaSamplers (to spend a loaded machine's time on some of them), else all.
std::vector<std::string> mitsuba_samplers() {
    const char* list = std::getenv("TIRPOL_MITSUBA_SAMPLERS");
    if (!list || !*list) return kMitsubaSamplers;
    std::vector<std::string> chosen;
    std::string rest = list;
    while (!rest.empty()) {
        const auto comma = rest.find(',');
        const std::string name = rest.substr(0, comma);
        rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
        if (std::find(kMitsubaSamplers.begin(), kMitsubaSamplers.end(), name) ==
            kMitsubaSamplers.end())
            throw Error("TIRPOL_MITSUBA_SAMPLERS: unknown sampler \"" + name +
                        "\"; expected comma-separated names from independent, stratified, "
                        "multijitter, orthogonal, ldsampler");
        chosen.push_back(name);
    }
    return chosen;
}

/// One scene of the comparison: its file, the pixels its noise is measured over, how Mitsuba's
/// version of it is written, and how far the two renderers' means may differ.
struct Comparison {
    std::string config;  ///< under config/, e.g. "scenes/reflection_compare.yaml"
    /// Objects whose pixels (centre ray) the noise is measured over; empty: every surface pixel.
    std::vector<std::string> noise_objects;
    std::function<std::filesystem::path(const std::filesystem::path&, const Scene&,
                                        const std::string&)>
        write_mitsuba;
    double max_relative_s0_difference = 0.0;  ///< |ΔS0|/S0 per region
    double max_ratio_difference = 0.0;        ///< |Δ(Sk/S0)| per region
};

/// Both renderers to 1 % noise on `comparison`'s scene, and the CPU-time ratio against Mitsuba's
/// best sampler (the body of ReflectionEqualNoise and EmissionEqualNoise).
void equal_noise(benchmark::State& state, const Comparison& comparison) {
    const int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    Scene scene = load_scene(find_config(comparison.config));
    RenderOptions options;
    options.threads = threads;
    std::vector<bool> mask;
    std::vector<NoiseRun> tirpol_runs;
    RenderPair tirpol;  // the last run: its means are the ones compared with Mitsuba's
    for (auto _ : state) {
        tirpol_runs.clear();
        for (int spp = 16; spp <= kMaxBracketSpp; spp *= 2) {
            RenderStatistics sa, sb;
            scene.sampling.samples_per_pixel = spp;
            scene.sampling.seed = 1;
            tirpol.a = render(scene, options, &sa);
            scene.sampling.seed = 2;
            tirpol.b = render(scene, options, &sb);
            if (mask.empty()) mask = noise_mask(scene, tirpol.a, comparison.noise_objects);
            tirpol.seconds = 0.5 * (sa.seconds - sa.setup_seconds + sb.seconds - sb.setup_seconds);
            tirpol.cpu_seconds = 0.5 * (sa.trace_cpu_seconds + sb.trace_cpu_seconds);
            tirpol_runs.push_back(
                {spp, relative_linear_noise(tirpol, mask), tirpol.seconds, tirpol.cpu_seconds});
            std::printf(
                "tirpol %5d spp, %d threads: %.2f s per render (%.2f CPU s), relative S1/S2 noise "
                "%.4f\n",
                spp, threads, tirpol.seconds, tirpol.cpu_seconds, tirpol_runs.back().noise);
            if (tirpol_runs.back().noise <= kTargetNoise) break;
        }
        state.SetIterationTime(tirpol.seconds);
    }
    if (tirpol_runs.size() < 2) {  // 16 spp already below 1 %: no bracket from above
        state.SkipWithError("tirpol's first run is already below the target noise: start lower");
        return;
    }
    const auto [tirpol_s, tirpol_cpu_s] = bracketed_seconds(tirpol_runs, kTargetNoise);
    state.counters["threads"] = threads;
    state.counters["tirpol_equal_noise_s"] = tirpol_s;
    state.counters["tirpol_equal_noise_cpu_s"] = tirpol_cpu_s;
    std::printf("tirpol to 1 %% (log-log between %d and %d spp): %.2f s wall, %.2f CPU s\n",
                tirpol_runs[tirpol_runs.size() - 2].spp, tirpol_runs.back().spp, tirpol_s,
                tirpol_cpu_s);

    const char* mitsuba = std::getenv("TIRPOL_MITSUBA");
    if (!mitsuba || !*mitsuba) {
        std::printf(
            "Mitsuba 3 comparison: skipped (set TIRPOL_MITSUBA to a mitsuba executable built with "
            "scalar_mono_polarized; docs/simulation.md)\n");
        return;
    }
    const auto dir = std::filesystem::temp_directory_path() / "tirpol_mitsuba_bench" /
                     std::filesystem::path(comparison.config).stem();
    std::filesystem::create_directories(dir);
    double best_cpu_s = std::numeric_limits<double>::infinity();
    std::string best;
    Agreement worst;  // over the samplers
    std::vector<std::string> samplers;
    try {
        samplers = mitsuba_samplers();
    } catch (const Error& e) {
        state.SkipWithError(e.what());
        return;
    }
    for (const std::string& sampler : samplers) {
        std::vector<NoiseRun> runs;
        RenderPair other;
        try {
            const auto xml = comparison.write_mitsuba(dir, scene, sampler);
            // Requests double, but past what the sampler rounded the last one up to, so that no
            // count is rendered twice (ldsampler: 32 becomes 64, and 64 would repeat it).
            for (int spp = 16; spp <= kMaxBracketSpp;
                 spp = std::max(2 * spp, other.samples_per_pixel + 1)) {
                other = render_mitsuba(mitsuba, xml, spp, threads, scene.camera);
                runs.push_back({other.samples_per_pixel, relative_linear_noise(other, mask),
                                other.seconds, other.cpu_seconds});
                std::printf(
                    "Mitsuba %-11s %5d spp (%5d asked): %.2f s per render (%.2f CPU s), relative "
                    "noise %.4f\n",
                    sampler.c_str(), other.samples_per_pixel, spp, other.seconds, other.cpu_seconds,
                    runs.back().noise);
                if (runs.back().noise <= kTargetNoise) break;
            }
            const Agreement agreement = check_agreement(scene, tirpol, other);
            worst.max_abs_z = std::max(worst.max_abs_z, agreement.max_abs_z);
            worst.max_relative_ds0 = std::max(worst.max_relative_ds0, agreement.max_relative_ds0);
            worst.max_ratio_difference =
                std::max(worst.max_ratio_difference, agreement.max_ratio_difference);
            state.counters["agree_max_abs_z"] = worst.max_abs_z;
            state.counters["agree_max_rel_dS0"] = worst.max_relative_ds0;
            state.counters["agree_max_d_ratio"] = worst.max_ratio_difference;
            if (agreement.max_relative_ds0 > comparison.max_relative_s0_difference ||
                agreement.max_ratio_difference > comparison.max_ratio_difference) {
                state.SkipWithError(
                    "tirpol and Mitsuba 3 disagree on the means (table above): different scenes, "
                    "no ratio");
                return;
            }
            const auto [other_s, other_cpu_s] = bracketed_seconds(runs, kTargetNoise);
            std::printf(
                "Mitsuba %-11s to 1 %% (log-log between %d and %d spp): %.2f s wall, %.2f CPU s; "
                "tirpol/Mitsuba %.2f (wall), %.2f (CPU)\n",
                sampler.c_str(), runs[runs.size() - 2].spp, runs.back().spp, other_s, other_cpu_s,
                tirpol_s / other_s, tirpol_cpu_s / other_cpu_s);
            state.counters["tirpol_over_" + sampler + "_cpu"] = tirpol_cpu_s / other_cpu_s;
            if (other_cpu_s < best_cpu_s) {
                best_cpu_s = other_cpu_s;
                best = sampler;
            }
        } catch (const Error& e) {
            state.SkipWithError(e.what());
            return;
        }
    }
    state.counters["tirpol_over_best_mitsuba_cpu"] = tirpol_cpu_s / best_cpu_s;
    std::printf("tirpol/Mitsuba (best sampler: %s) equal-noise CPU time ratio at 1 %%: %.2f\n",
                best.c_str(), tirpol_cpu_s / best_cpu_s);
}

void BM_ReflectionEqualNoise(benchmark::State& state) {
    // The two renderers' means may differ by their documented model differences (Mitsuba's
    // uncorrelated Smith G on the rough plane: −1 % in S0 at grazing rows, −0.4 % over the plane);
    // a mistranslated scene (sky, index, geometry, frames) differs by far more, and then no ratio
    // is reported.
    equal_noise(state, {"scenes/reflection_compare.yaml", {}, write_reflection_scene, 0.01, 0.005});
}
BENCHMARK(BM_ReflectionEqualNoise)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

void BM_EmissionEqualNoise(benchmark::State& state) {
    // Noise over the spheres: the walls' S1 and S2 are exactly 0 in both renderers (Lambertian
    // reflection depolarizes), so over all pixels they would only dilute it. Tolerances as for the
    // reflection scene (the rough spheres meet the same Smith G difference at their rims).
    equal_noise(
        state,
        {"scenes/emission_compare.yaml", {"paint", "metal"}, write_emission_scene, 0.01, 0.005});
}
BENCHMARK(BM_EmissionEqualNoise)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

/// How emission_compare's radiance arrives, per object and over the whole image: the share of S0
/// that is the surface's own emission (reflections capped at 0), that arrives after one reflection
/// of another surface's emission (cap 1, less cap 0), and after more; and the share of the linear
/// polarization (S1, S2) that one reflection carries, as Σ(S·S_full)/Σ(S_full·S_full′) with
/// S_full, S_full′ two full renders of other seeds (unbiased by their noise), printed where the
/// polarization is more than rounding (rms of S1, S2 > 1e-4 S0; Lambertian walls have none). An
/// object's pixels are those whose centre ray and its 8 neighbours' hit it, so that no pixel mixes
/// in the wall behind a sphere's rim. Plain estimator (the control variate adds a term per hit that
/// a cap would cut through). Figures, not speed.
void BM_EmissionPaths(benchmark::State& state) {
    Scene scene = load_scene(find_config("scenes/emission_compare.yaml"));
    scene.sampling.samples_per_pixel = 256;
    RenderOptions plain;
    plain.control_variate = false;
    const auto render_with = [&](int max_bounces, std::uint64_t seed) {
        scene.sampling.max_bounces = max_bounces;
        scene.sampling.seed = seed;
        return render(scene, plain);
    };
    for (auto _ : state) {
        const Image own = render_with(0, 3), one = render_with(1, 4),
                    full = render_with(kDefaultMaxBounces, 1),
                    full2 = render_with(kDefaultMaxBounces, 2);
        const auto& ids = full.channel("object_id");
        const auto interior_of = [&](int x, int y) {
            const float id = ids[full.index(x, y)];
            if (x == 0 || y == 0 || x + 1 == full.width() || y + 1 == full.height()) return -1.0f;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    if (ids[full.index(x + dx, y + dy)] != id) return -1.0f;
            return id;
        };
        std::printf(
            "emission_compare %dx%d, %d spp, plain estimator: share of S0 and of the linear "
            "polarization by path\n",
            full.width(), full.height(), scene.sampling.samples_per_pixel);
        // Rows: each object's interior pixels, then every pixel of the image (object −1 here).
        for (int object = 0; object <= static_cast<int>(scene.objects.size()); ++object) {
            const bool whole_image = object == static_cast<int>(scene.objects.size());
            double s0_own = 0.0, s0_one = 0.0, s0_full = 0.0, lin_one = 0.0, lin_full = 0.0;
            std::size_t pixels = 0;
            for (int y = 0; y < full.height(); ++y)
                for (int x = 0; x < full.width(); ++x) {
                    if (!whole_image && interior_of(x, y) != static_cast<float>(object)) continue;
                    const std::size_t i = full.index(x, y);
                    ++pixels;
                    s0_own += own.channel("S0")[i];
                    s0_one += one.channel("S0")[i];
                    s0_full += 0.5 * (full.channel("S0")[i] + full2.channel("S0")[i]);
                    for (const char* c : {"S1", "S2"}) {
                        lin_one += one.channel(c)[i] * full.channel(c)[i];
                        lin_full += full2.channel(c)[i] * full.channel(c)[i];
                    }
                }
            if (pixels == 0) continue;
            std::printf("  %-8s %6zu px  S0: own emission %.3f, one reflection %.3f, more %.3f",
                        whole_image ? "image"
                                    : scene.objects[static_cast<std::size_t>(object)].name.c_str(),
                        pixels, s0_own / s0_full, (s0_one - s0_own) / s0_full,
                        (s0_full - s0_one) / s0_full);
            const auto n = static_cast<double>(pixels);
            if (lin_full > 0.0 && std::sqrt(lin_full / n) > 1e-4 * s0_full / n)
                std::printf("  S1/S2: one reflection %.3f, more %.3f", lin_one / lin_full,
                            1.0 - lin_one / lin_full);
            std::printf("\n");
        }
        state.SetIterationTime(1.0);
    }
}
BENCHMARK(BM_EmissionPaths)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

}  // namespace
