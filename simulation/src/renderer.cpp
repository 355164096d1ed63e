#include "tirpol/simulation/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <memory>

#include "render_memory.h"
#include "rng.h"
#include "sobol_sampler.h"
#include "surface_basis.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/interrupt_signals.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/log.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/core/stokes.h"
#include "tirpol/materials/emissivity.h"

namespace tirpol::simulation {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Offset of a new ray's origin off the surface, relative to the scene's scale (float BVH).
double ray_epsilon(const Vec3& p) { return 1e-5 * (1.0 + p.cwiseAbs().maxCoeff()); }

/// CPU time of the calling thread: what a tile costs, whatever else the machine runs.
std::uint64_t thread_cpu_ns() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<std::uint64_t>(t.tv_sec) * 1000000000ULL +
           static_cast<std::uint64_t>(t.tv_nsec);
}

/// m · R, where R = frame_rotation(frame_rotation_angle(from, to)) re-expresses Stokes given in
/// `from` = surface_frame(k, n) in a frame `to` of the same propagation k given by its reference
/// axis (any length, and any component along k, which drops out of the dot products with vectors
/// across k). R only mixes S1 and S2, so only m's columns 1 and 2 change, and cos 2α, sin 2α come
/// from dot products (no trig): surface_frame's reference is n × k normalised and its second axis
/// k × reference, and the lengths cancel in (c² − s²)/(c² + s²) and 2cs/(c² + s²), so neither frame
/// is normalised. Where n × k vanishes (a beam along the normal) surface_frame's fallback axis is
/// used.
MuellerMatrix times_rotation(const MuellerMatrix& m, const Vec3& k, const Vec3& n,
                             const Vec3& to_reference) {
    Vec3 from_reference = n.cross(k);
    if (!(from_reference.squaredNorm() > 1e-280)) from_reference = surface_frame(k, n).reference;
    const double c = to_reference.dot(from_reference),
                 s = to_reference.dot(k.cross(from_reference));
    const double norm = c * c + s * s;
    const double c2 = (c * c - s * s) / norm, s2 = 2.0 * c * s / norm;
    MuellerMatrix out = m;
    out.col(1) = c2 * m.col(1) - s2 * m.col(2);
    out.col(2) = s2 * m.col(1) + c2 * m.col(2);
    return out;
}

/// leaving · v, where `rotation_only` says that `leaving` is a rotation of S1 and S2 alone (at a
/// path's first vertex, as the throughput before it is the identity): then only v's S1 and S2 mix,
/// the same doubles as the full product, whose other terms add zeros.
StokesVector leaving_times(const MuellerMatrix& leaving, const StokesVector& v,
                           bool rotation_only) {
    if (!rotation_only) return leaving * v;
    return {v(0), leaving(1, 1) * v(1) + leaving(1, 2) * v(2),
            leaving(2, 1) * v(1) + leaving(2, 2) * v(2), v(3)};
}

/// The spectrum that shapes the wavelength draw at `lambda_um`: the sum of the objects' Planck
/// spectra at the middle of their temperature ranges (290 K without objects). A sum and not
/// Planck's law at the mean temperature: a room of walls at 275–340 K and cold spheres (1 K) has a
/// mean of 228 K, whose spectrum is 2.2× steeper across 8–14 µm than the walls' radiance, while the
/// sum follows the objects that emit and ignores those that do not.
double wavelength_shape(const Scene& scene, double lambda_um) {
    if (scene.objects.empty()) return planck_radiance(lambda_um, 290.0);
    double sum = 0.0;
    for (const auto& o : scene.objects)
        sum += planck_radiance(lambda_um, 0.5 * (o.temperature.min_k() + o.temperature.max_k()));
    return sum;
}

/// Everything a path needs that does not change during a render.
class PathTracer {
public:
    PathTracer(const Scene& scene, const std::filesystem::path& cache_dir, RenderStatistics& stats,
               RayRecorder* recorder, bool control_variate)
        : m_scene(scene), m_recorder(recorder), m_control_variate(control_variate) {
        std::vector<BandNode> nodes = spectral_grid(scene.band).nodes();
        // Increasing wavelengths: the emissivity tables' columns.
        std::sort(nodes.begin(), nodes.end(), [](const BandNode& a, const BandNode& b) {
            return a.wavelength_um < b.wavelength_um;
        });
        double band_weight_um = 0.0;
        for (const auto& node : nodes) band_weight_um += node.weight_um;
        if (!(band_weight_um > 0.0))
            fail("band {}–{} µm: the spectral response is zero everywhere", scene.band.lo_um(),
                 scene.band.hi_um());
        // Nodes are drawn ∝ weight·B(λ), B the sum of the objects' Planck spectra
        // (wavelength_shape): a thermal scene's radiance is a mixture of such spectra, so L(λ)/B(λ)
        // changes little from node to node and the spectral part of the noise, which a replicate
        // of few points stratifies only coarsely, mostly cancels. Any B is unbiased (the estimate
        // divides by the probability); uniform in weight where Planck's law underflows (short
        // bands, cold scenes).
        std::vector<double> shape;
        for (const auto& node : nodes) shape.push_back(wavelength_shape(scene, node.wavelength_um));
        if (!std::all_of(shape.begin(), shape.end(),
                         [](double b) { return std::isfinite(b) && b > 1e-30; }))
            shape.assign(nodes.size(), 1.0);
        double total = 0.0;
        for (std::size_t k = 0; k < nodes.size(); ++k) {
            m_wavelengths.push_back(nodes[k].wavelength_um);
            total += nodes[k].weight_um * shape[k];
            m_cdf.push_back(total);
        }
        for (auto& c : m_cdf) c /= total;
        // Guide table (Chen & Asau 1974): m_node_guide[j] is the node std::lower_bound gives for
        // j/G, so a draw u in [j/G, (j + 1)/G] lies between two entries and the search in trace()
        // looks at a node or two instead of bisecting all of them.
        const std::size_t guide_steps = 4 * m_cdf.size();
        for (std::size_t j = 0; j <= guide_steps; ++j)
            m_node_guide.push_back(node_at_or_above(
                0, m_cdf.size(), static_cast<double>(j) / static_cast<double>(guide_steps)));
        for (std::size_t k = 0; k < nodes.size(); ++k) m_node_scale_um.push_back(total / shape[k]);
        // What depends only on the wavelength node (and an object's constant temperature) is
        // evaluated here once instead of at every hit: Planck's law for the sky, the sun and each
        // object.
        const std::size_t node_count = m_wavelengths.size();
        for (const double lambda : m_wavelengths) {
            m_sky_at_node.push_back(scene.sky.at_wavelength(lambda));
            m_sun_at_node.push_back(scene.sun ? scene.sun->spectral_radiance(lambda) : 0.0);
        }
        m_object_blackbody.assign(scene.objects.size() * node_count, kNaN);
        for (std::size_t o = 0; o < scene.objects.size(); ++o) {
            const TemperatureField& field = scene.objects[o].temperature;
            if (!field.is_constant()) continue;
            for (std::size_t k = 0; k < node_count; ++k)
                m_object_blackbody[o * node_count + k] =
                    planck_radiance(m_wavelengths[k], field.min_k());
        }
        for (const auto& m : scene.materials) {
            const auto [lo, hi] = m.brdf->valid_wavelength_range_um();
            if (scene.band.lo_um() < lo || scene.band.hi_um() > hi)
                fail(
                    "material '{}' ({}) is defined over {}–{} µm, which does not cover the band "
                    "{}–{} µm",
                    m.name, m.source, lo, hi, scene.band.lo_um(), scene.band.hi_um());
        }
        // Emission is looked up at exactly the path's wavelength node (a table column per node), so
        // ε + ρ = 1 holds per path and an isothermal enclosure is a blackbody whatever n,k(λ) does.
        // Materials are independent: their tables come from the cache or are built in parallel.
        m_emissivity.resize(scene.materials.size());
        std::vector<materials::EmissivityCacheSource> sources(scene.materials.size());
        tbb::parallel_for(std::size_t{0}, scene.materials.size(), [&](std::size_t i) {
            auto cached = materials::cached_emissivity_table(*scene.materials[i].brdf,
                                                             m_wavelengths, cache_dir);
            m_emissivity[i] = std::move(cached.table);
            sources[i] = cached.source;
        });
        for (const auto source : sources) {
            if (source == materials::EmissivityCacheSource::memory)
                ++stats.emissivity_tables_from_memory;
            else if (source == materials::EmissivityCacheSource::disk)
                ++stats.emissivity_tables_from_disk;
            else
                ++stats.emissivity_tables_built;
        }
    }

    /// One sample of the band radiance arriving at the camera along `direction`, in the camera's
    /// Stokes frame of that ray (PinholeCamera::image_frame), given by `camera_right`, the camera's
    /// x axis: image_frame's reference is that axis with its component along the ray removed and
    /// normalised, and the frame rotations (times_rotation) need neither, as only its dot products
    /// with vectors across the ray enter them; `sampler` gives the wavelength node's number and
    /// each bounce's (sobol_sampler.h).
    StokesVector trace(Vec3 origin, Vec3 direction, const Vec3& camera_right, PathSampler& sampler,
                       std::uint64_t& scene_rays, std::uint64_t& shadow_rays) const {
        const std::size_t k = std::min(wavelength_node(sampler.wavelength()), m_cdf.size() - 1);
        const double lambda = m_wavelengths[k];
        const Sky::AtWavelength& sky = m_sky_at_node[k];
        const Sun* sun = m_scene.sun ? &*m_scene.sun : nullptr;
        const double sun_radiance = m_sun_at_node[k];

        // Maps Stokes of light travelling along −direction, given in `frame`, to the camera frame.
        // The frame is the s/p frame of the last surface (first: the camera's), so each vertex
        // needs one rotation, from its own s/p frame of the same ray (paper eq 12's two rotations
        // through the world frame compose into this one).
        MuellerMatrix throughput = MuellerMatrix::Identity();
        Vec3 frame_reference = camera_right;  // of the frame throughput takes its Stokes in
        StokesVector radiance = StokesVector::Zero();
        bool last_was_delta = true;  // the camera sees the sun's disk directly
        const int max_bounces = m_scene.sampling.max_bounces;
        for (int bounce = 0;; ++bounce) {
            ++scene_rays;
            if (m_recorder) m_recorder->record(origin, direction, 1e30, false);
            const auto hit = m_scene.tracer->intersect(origin, direction);
            if (!hit) {
                double l = sky.spectral_radiance(direction);
                if (sun && last_was_delta &&
                    direction.dot(sun->direction) >= sun->cos_angular_radius())
                    l += sun_radiance;
                radiance += throughput.col(0) * l;
                break;
            }
            const Vec3 wo = -direction;
            Vec3 ng = hit->geometric_normal, ns = hit->shading_normal;
            if (ng.dot(wo) <
                0.0) {  // back face of a thin surface: shade the side the ray came from
                ng = -ng;
                ns = -ns;
            }
            const Vec3 n = ns.dot(wo) > 1e-9 ? ns : ng;
            const detail::SurfaceBasis basis(n);
            const Vec3 wo_local = basis.to_local(wo);
            const SceneObject& object = m_scene.objects[hit->object];
            const std::uint32_t material = object.material_at(hit->primitive);
            const materials::PolarizedBrdf& brdf = *m_scene.materials[material].brdf;
            const double blackbody = object_blackbody(*hit, k);

            // Surface-leaving Stokes is expressed in surface_frame(wo, n) (pbrdf.h); rotate into
            // the ray's frame.
            const MuellerMatrix leaving = times_rotation(throughput, wo, n, frame_reference);
            const StokesVector emissivity =
                m_emissivity[material]->at(std::clamp(wo_local.z(), 0.0, 1.0), k);
            radiance += leaving_times(leaving, emissivity, bounce == 0) * blackbody;  // eq 13
            if (bounce >= max_bounces)
                break;  // safety cap only: Russian roulette ends paths (below)

            // Control variate for the reflected radiance ∫M·L_in·cosθi dωi (renderer.h): its exact
            // value for an unpolarized incident radiance L_ref, (e0 − ε)·L_ref by Kirchhoff's law
            // (the same table as the emission), plus the sampled estimate of ∫M·(L_in −
            // L_ref)·cosθi dωi.
            const double l_ref =
                m_control_variate ? reference_radiance(wo, n, sky, blackbody) : 0.0;
            radiance +=
                leaving_times(leaving, StokesVector::UnitX() - emissivity, bounce == 0) * l_ref;

            const Vec3 p = hit->position + ray_epsilon(hit->position) * ng;
            if (sun && sun->direction.dot(n) > 0.0 && sun->direction.dot(ng) > 0.0) {
                ++shadow_rays;
                if (m_recorder) m_recorder->record(p, sun->direction, 1e30, true);
                if (!m_scene.tracer->occluded(p, sun->direction, 0.0, 1e30)) {
                    const Vec3 wi_local = basis.to_local(sun->direction);
                    const MuellerMatrix f = brdf.eval(wi_local, wo_local, lambda);
                    // The sun is unpolarized: only the first column of M acts, in any incident
                    // frame.
                    radiance +=
                        leaving * f.col(0) * (wi_local.z() * sun->solid_angle_sr * sun_radiance);
                }
            }

            // Every bounce has its own stratified pair (the first two in the path's Sobol prefix,
            // jointly with the sub-pixel position and wavelength; deeper ones padded), so the lobe
            // choice behind a mirror (the glossy paint seen in it) is as evenly spread over a
            // pixel's samples as the first.
            const auto [u1, u2] = sampler.scatter(bounce);
            const materials::BrdfSample s = brdf.sample(wo_local, lambda, u1, u2);
            if (!(s.pdf > 0.0)) break;
            const Vec3 wi = basis.to_world(s.wi).normalized();
            if (wi.dot(ng) <=
                0.0) {  // shading normal sent the path under the surface: L_in = 0 there
                radiance -= leaving * s.weight.col(0) * l_ref;
                break;
            }
            // eq 12: incident light travels along −wi; the pBRDF takes its Stokes in
            // surface_frame(−wi, n).
            if (bounce == 0) {
                // The throughput before the first vertex is the identity, so `leaving` is the
                // rotation alone and its product with the weight only mixes the weight's rows 1
                // and 2: the same doubles as the full product, whose other terms add zeros.
                throughput = s.weight;
                throughput.row(1) =
                    leaving(1, 1) * s.weight.row(1) + leaving(1, 2) * s.weight.row(2);
                throughput.row(2) =
                    leaving(2, 1) * s.weight.row(1) + leaving(2, 2) * s.weight.row(2);
            } else {
                throughput = leaving * s.weight;
            }
            frame_reference = n.cross(-wi);
            if (!(frame_reference.squaredNorm() > 1e-280))
                frame_reference = surface_frame(-wi, n).reference;
            last_was_delta = s.is_delta;

            // Russian roulette from the fifth hit on ends paths without bias: a path survives with
            // probability q = clamp(S0 throughput, 0.25, 1) and is then weighted by 1/q (Arvo &
            // Kirk, SIGGRAPH 1990). Deep mirror traps (a closed metal box) are followed as far as
            // they carry radiance, where a fixed bounce limit would drop it. The floor keeps
            // survivors' weights bounded (≤ 4× the throughput): with q = throughput alone a grey
            // diffuse enclosure (albedo 0.3) kept 1 path in 37 at ×37 weight, and pixels that drew
            // no survivor read 1 % low with a variance estimate that could not show it. Not from
            // the third hit: in a closed room (emission_compare) a third of the spheres'
            // polarization arrives after two or more wall reflections, and ×4 survivors there
            // doubled the noise at 256 spp (ConvergenceExponent, docs/simulation.md). Cost: a path
            // in a closed scene takes at least five hits (1.6× the CPU time there), open scenes
            // hardly change.
            if (bounce >= 4) {
                constexpr double kMinSurvival = 0.25;
                const double survive = std::clamp(throughput(0, 0), kMinSurvival, 1.0);
                if (!(survive > 0.0) || sampler.roulette(bounce) >= survive) break;
                throughput /= survive;
            }
            // The control variate's −L_ref, carried by the same (roulette-weighted) throughput as
            // the L_in that the continuing path collects; unpolarized, so only the first column
            // acts.
            radiance -= throughput.col(0) * l_ref;
            origin = p;
            direction = wi;
        }
        return radiance * m_node_scale_um[k];
    }

private:
    /// The first node in [first, last) whose CDF value is ≥ u (last if none).
    std::size_t node_at_or_above(std::size_t first, std::size_t last, double u) const {
        const auto begin = m_cdf.begin();
        return static_cast<std::size_t>(std::lower_bound(begin + static_cast<std::ptrdiff_t>(first),
                                                         begin + static_cast<std::ptrdiff_t>(last),
                                                         u) -
                                        begin);
    }

    /// The wavelength node that the draw u selects: the first whose CDF value is ≥ u, the same
    /// node as a search of all nodes. The guide entries one step either side of u's bracket bound
    /// it whatever the rounding of u·G.
    std::size_t wavelength_node(double u) const {
        const std::size_t steps = m_node_guide.size() - 1;
        const auto j = static_cast<std::size_t>(
            std::clamp(u * static_cast<double>(steps), 0.0, static_cast<double>(steps - 1)));
        return node_at_or_above(m_node_guide[j > 0 ? j - 1 : 0],
                                m_node_guide[std::min(j + 2, steps)], u);
    }

    /// L_ref of the control variate at a vertex (any value that does not depend on the sampled wi
    /// keeps the estimate unbiased; the closer to the incident radiance, the lower the variance):
    /// the sky along the mirror direction of wo, where most of a glossy lobe looks in an open
    /// scene, or the vertex's own blackbody radiance when that direction is below the horizon
    /// (ground, walls, closed scenes, where the surroundings are near the surface's temperature).
    double reference_radiance(const Vec3& wo, const Vec3& n, const Sky::AtWavelength& sky,
                              double blackbody) const {
        const Vec3 mirror = 2.0 * n.dot(wo) * n - wo;
        return mirror.z() > 0.0 ? sky.spectral_radiance(mirror) : blackbody;
    }

    /// L_bb(λ_k, T) at a hit: from the table for objects of constant temperature, else evaluated.
    double object_blackbody(const SurfaceHit& hit, std::size_t k) const {
        const double tabulated = m_object_blackbody[hit.object * m_wavelengths.size() + k];
        if (!std::isnan(tabulated)) return tabulated;
        const double temperature =
            m_scene.objects[hit.object].temperature.at(hit, m_scene.tracer->mesh(hit.object));
        return planck_radiance(m_wavelengths[k], temperature);
    }

    const Scene& m_scene;
    RayRecorder* m_recorder;
    bool m_control_variate;
    std::vector<double> m_cdf, m_wavelengths;
    std::vector<std::size_t> m_node_guide;  ///< wavelength_node's guide table (constructor)
    std::vector<double>
        m_node_scale_um;  ///< Σ_j w_j·L_bb(λ_j)/L_bb(λ_k): the estimate's factor at node k
    std::vector<Sky::AtWavelength> m_sky_at_node;  // per wavelength node
    std::vector<double> m_sun_at_node;  // sun's spectral radiance per node (0 without a sun)
    std::vector<double>
        m_object_blackbody;  // [object][node]: L_bb at a constant temperature, else NaN
    std::vector<std::shared_ptr<const materials::EmissivityTable>> m_emissivity;
};

/// Mean of a pixel and the variance of that mean from R i.i.d. replicate means m_r (each the mean
/// of an independently scrambled set of points): m̄ = Σ m_r / R, Var(m̄) = Σ (m_r − m̄)² / (R(R − 1)),
/// unbiased because the replicates are independent and identically distributed (L'Ecuyer & Lemieux
/// 2002). Welford's update keeps it exact in floating point. NaN variance with one replicate.
class ReplicateMean {
public:
    void add(const StokesVector& replicate_mean) {
        ++m_count;
        const StokesVector delta = replicate_mean - m_mean;
        m_mean += delta / m_count;
        m_sum_squares += delta.cwiseProduct(replicate_mean - m_mean);
    }
    const StokesVector& mean() const { return m_mean; }
    StokesVector variance_of_mean() const {
        if (m_count < 2) return StokesVector::Constant(kNaN);
        return m_sum_squares / (m_count * (m_count - 1.0));
    }

private:
    int m_count = 0;
    StokesVector m_mean = StokesVector::Zero(), m_sum_squares = StokesVector::Zero();
};

struct Channels {
    explicit Channels(Image& image)
        : s0(image.add_channel("S0")),
          s1(image.add_channel("S1")),
          s2(image.add_channel("S2")),
          s3(image.add_channel("S3")),
          dolp(image.add_channel("DoLP")),
          aop(image.add_channel("AoP")),
          s0_var(image.add_channel("S0_var")),
          s1_var(image.add_channel("S1_var")),
          s2_var(image.add_channel("S2_var")),
          s3_var(image.add_channel("S3_var")),
          depth(image.add_channel("depth")),
          nx(image.add_channel("normal_x")),
          ny(image.add_channel("normal_y")),
          nz(image.add_channel("normal_z")),
          view_zenith(image.add_channel("view_zenith_deg")),
          object_id(image.add_channel("object_id")),
          material_id(image.add_channel("material_id")),
          temperature(image.add_channel("temperature_k")) {}
    std::vector<float>&s0, &s1, &s2, &s3, &dolp, &aop, &s0_var, &s1_var, &s2_var, &s3_var, &depth,
        &nx, &ny, &nz, &view_zenith, &object_id, &material_id, &temperature;
    std::array<std::vector<float>*, 18> all() {
        return {&s0,     &s1,     &s2,          &s3,        &dolp,        &aop,
                &s0_var, &s1_var, &s2_var,      &s3_var,    &depth,       &nx,
                &ny,     &nz,     &view_zenith, &object_id, &material_id, &temperature};
    }
};

}  // namespace

std::uint64_t render_memory_estimate_bytes(int width, int height) {
    // 18 float channels (Channels), plus at most 4 bytes a pixel more while a quicklook or an EXR
    // line buffer is written. Samples cost nothing: the sampler computes every number
    // (sobol_sampler.h).
    constexpr std::uint64_t kImageBytesPerPixel = 18 * sizeof(float) + 4 * sizeof(float);
    const auto pixels = static_cast<std::uint64_t>(std::max(width, 0)) *
                        static_cast<std::uint64_t>(std::max(height, 0));
    return pixels * kImageBytesPerPixel;
}

Band spectral_grid(const Band& band) {
    return Band(band.lo_um(), band.hi_um(), band.rsr(), kSpectralGridPanel_um);
}

Image render(const Scene& scene, const RenderOptions& options, RenderStatistics* statistics) {
    const auto start = std::chrono::steady_clock::now();
    const int spp_requested = scene.sampling.samples_per_pixel;
    if (spp_requested < 1 || spp_requested > limits::kMaxSamplesPerPixel)
        fail("sampling.spp {}: expected 1 to {} samples per pixel (limits.h)", spp_requested,
             limits::kMaxSamplesPerPixel);
    const int workers = options.threads > 0 ? options.threads : tbb::info::default_concurrency();
    check_memory_estimate(
        render_memory_estimate_bytes(scene.camera.width(), scene.camera.height()),
        fmt::format("render of {}×{} pixels at {} spp on {} threads", scene.camera.width(),
                    scene.camera.height(), spp_requested, workers));
    tbb::task_arena arena(workers);
    RenderStatistics stats;
    const std::filesystem::path cache_dir = options.emissivity_cache_dir
                                                ? *options.emissivity_cache_dir
                                                : materials::default_emissivity_cache_directory();
    const bool control_variate =
        options.control_variate.value_or(scene.sampling.estimator == Estimator::control_variate);
    std::unique_ptr<const PathTracer> tracer_ptr;
    arena.execute([&] {
        tracer_ptr = std::make_unique<const PathTracer>(scene, cache_dir, stats,
                                                        options.ray_recorder, control_variate);
    });
    const PathTracer& tracer = *tracer_ptr;
    const double setup_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const PinholeCamera& camera = scene.camera;
    const Vec3 camera_right =
        camera.world_from_camera().col(0);  // never along a ray: every ray looks forward
    const int w = camera.width(), h = camera.height();
    const int replicates = replicate_count(scene.sampling);
    const int spp = rendered_samples_per_pixel(scene.sampling);
    const auto points = static_cast<std::uint32_t>(spp / replicates);  // per replicate
    if (spp != scene.sampling.samples_per_pixel)
        spdlog::warn("render: {} samples per pixel rounded up to {} ({} replicates of {} points)",
                     scene.sampling.samples_per_pixel, spp, replicates, points);
    const std::uint64_t seed = scene.sampling.seed;
    if (options.pixel_mask &&
        options.pixel_mask->size() != static_cast<std::size_t>(w) * static_cast<std::size_t>(h))
        fail("render: the pixel mask has {} entries; expected {}×{} = {}",
             options.pixel_mask->size(), w, h,
             static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    Image image(w, h);
    Channels ch(image);

    const int tile = std::max(1, options.tile_size);
    const int tiles_x = (w + tile - 1) / tile, tiles_y = (h + tile - 1) / tile;
    const auto tile_count = static_cast<std::size_t>(tiles_x) * static_cast<std::size_t>(tiles_y);
    std::unique_ptr<ProgressReporter> progress;
    if (options.show_progress) progress = std::make_unique<ProgressReporter>("render", tile_count);
    std::atomic<std::uint64_t> scene_rays{0}, shadow_rays{0}, trace_cpu_ns{0};

    auto render_tile = [&](std::size_t tile_index) {
        if (options.cancel && options.cancel->load(std::memory_order_relaxed)) return;
        const int tx = static_cast<int>(tile_index % static_cast<std::size_t>(tiles_x));
        const int ty = static_cast<int>(tile_index / static_cast<std::size_t>(tiles_x));
        const std::uint64_t cpu_start_ns = thread_cpu_ns();
        std::uint64_t rays = 0, shadows = 0;
        for (int y = ty * tile; y < std::min(h, (ty + 1) * tile); ++y) {
            for (int x = tx * tile; x < std::min(w, (tx + 1) * tile); ++x) {
                const std::size_t i = image.index(x, y);
                // A masked pixel skips every replicate: its channels are NaN and it draws no
                // samples.
                if (options.pixel_mask && !(*options.pixel_mask)[i]) {
                    for (auto* c : ch.all()) (*c)[i] = static_cast<float>(kNaN);
                    continue;
                }
                ReplicateMean pixel;
                for (std::uint32_t r = 0; r < static_cast<std::uint32_t>(replicates); ++r) {
                    const ReplicateSampler replicate(seed, i, r, points);
                    StokesVector sum = StokesVector::Zero();
                    for (std::uint32_t s = 0; s < points; ++s) {
                        PathSampler sampler(replicate, s, seed, i, std::uint64_t{r} * points + s);
                        const auto [du, dv] = sampler.subpixel();
                        const Vec3 d = camera.ray_direction(x + du, y + dv);
                        sum += tracer.trace(camera.position(), d, camera_right, sampler, rays,
                                            shadows);
                    }
                    pixel.add(sum / points);
                }
                const StokesVector& mean = pixel.mean();
                ch.s0[i] = static_cast<float>(mean[0]);
                ch.s1[i] = static_cast<float>(mean[1]);
                ch.s2[i] = static_cast<float>(mean[2]);
                ch.s3[i] = static_cast<float>(mean[3]);
                ch.dolp[i] = static_cast<float>(tirpol::dolp(mean));
                ch.aop[i] = static_cast<float>(aop_deg_0_180(mean));
                const StokesVector var = pixel.variance_of_mean();
                ch.s0_var[i] = static_cast<float>(var[0]);
                ch.s1_var[i] = static_cast<float>(var[1]);
                ch.s2_var[i] = static_cast<float>(var[2]);
                ch.s3_var[i] = static_cast<float>(var[3]);

                // Auxiliary channels from the pixel-centre ray.
                const Vec3 d = camera.ray_direction(x + 0.5, y + 0.5);
                ++rays;
                if (options.ray_recorder)
                    options.ray_recorder->record(camera.position(), d, 1e30, false);
                const auto hit = scene.tracer->intersect(camera.position(), d);
                if (hit) {
                    Vec3 n = hit->shading_normal;
                    if (hit->geometric_normal.dot(d) > 0.0) n = -n;
                    const SceneObject& obj = scene.objects[hit->object];
                    ch.depth[i] = static_cast<float>(hit->distance);
                    ch.nx[i] = static_cast<float>(n.x());
                    ch.ny[i] = static_cast<float>(n.y());
                    ch.nz[i] = static_cast<float>(n.z());
                    ch.view_zenith[i] =
                        static_cast<float>(rad_to_deg(std::acos(std::clamp(-n.dot(d), -1.0, 1.0))));
                    ch.object_id[i] = static_cast<float>(hit->object);
                    ch.material_id[i] = static_cast<float>(obj.material_at(hit->primitive));
                    ch.temperature[i] = static_cast<float>(
                        obj.temperature.at(*hit, scene.tracer->mesh(hit->object)));
                } else {
                    for (auto* c :
                         {&ch.depth, &ch.nx, &ch.ny, &ch.nz, &ch.view_zenith, &ch.temperature})
                        (*c)[i] = static_cast<float>(kNaN);
                    ch.object_id[i] = ch.material_id[i] = -1.0f;
                }
            }
        }
        scene_rays += rays;
        shadow_rays += shadows;
        trace_cpu_ns += thread_cpu_ns() - cpu_start_ns;
        if (progress) progress->advance();
    };

    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tile_count, 1),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                              for (std::size_t t = r.begin(); t != r.end(); ++t) render_tile(t);
                          });
    });
    if (options.cancel && options.cancel->load()) throw Cancelled("render cancelled");
    if (progress) progress->finish();

    const CameraModel& lens = scene.camera.lens_model();
    write_stokes_image_header(
        image, {.units = "W/(m^2 sr) band radiance",
                .band_um = std::array{scene.band.lo_um(), scene.band.hi_um()},
                // Degrees of freedom of the S*_var channels (R − 1 for R i.i.d. replicates), so
                // that a comparison can allow for the Student-t tails of a ratio with an
                // estimated variance.
                .variance_dof = replicates - 1,
                // The lens rendered through (OpenCV pixel convention), so a comparison can check
                // that it is the measured camera's calibrated model
                // (report::register_by_camera_model).
                .camera_intrinsics_px = std::array{lens.fx, lens.fy, lens.cx, lens.cy},
                .camera_distortion = lens.distortion});
    auto& attrs = image.attributes();
    attrs["band_rsr"] = std::string(scene.band.rsr() ? "yes" : "none");
    attrs["spp"] = spp;
    attrs["replicates"] = replicates;
    attrs["seed"] = std::to_string(seed);
    attrs["max_bounces"] = scene.sampling.max_bounces;
    attrs["estimator"] = std::string(
        estimator_name(control_variate ? Estimator::control_variate : Estimator::plain));
    attrs["scene_file"] = scene.file.string();
    attrs["stokes_frame"] = std::string(
        "camera: 0 deg = camera right projected onto each ray wavefront, 90 deg toward the image "
        "top; S1 = I0 - I90; "
        "S3 > 0 right-circular seen by the receiver");
    attrs["renderer"] = std::string("tirpol polarized path tracer (Embree 3, TBB)");

    if (statistics) {
        *statistics = stats;
        statistics->seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        statistics->setup_seconds = setup_seconds;
        statistics->trace_cpu_seconds = static_cast<double>(trace_cpu_ns.load()) * 1e-9;
        statistics->camera_rays = static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h) *
                                  static_cast<std::uint64_t>(spp);
        statistics->scene_rays = scene_rays.load();
        statistics->shadow_rays = shadow_rays.load();
    }
    return image;
}

}  // namespace tirpol::simulation
