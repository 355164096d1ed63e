#pragma once
/// \file scene.h
/// A scene ready to render: geometry in Embree, a material and a temperature field per object, the
/// sky, the sun, the camera, the spectral band and the sampling settings. Loaded from the YAML
/// scene format of docs/scene-format.md.
///
/// Downwelling sky radiance for rays that leave the scene, and the sun. The sky is unpolarized
/// (a clear LWIR night sky is, to first order; the paper's MODTRAN-P polarized sky is not
/// modelled).
///
/// The temperature of an object's surface: one value, per-vertex values (interpolated across each
/// triangle) or a texture map looked up by the surface's (u, v). The thermal solver of a later
/// issue fills the same per-vertex form.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tirpol/core/config.h"
#include "tirpol/core/geometry.h"
#include "tirpol/core/image.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/materials/pbrdf.h"
#include "tirpol/simulation/pinhole_camera.h"
#include "tirpol/simulation/ray_tracer.h"

namespace tirpol::simulation {

class TemperatureField {
public:
    static TemperatureField constant(double temperature_k);
    /// One temperature per mesh vertex, in the mesh's vertex order.
    static TemperatureField per_vertex(std::vector<double> temperatures_k);
    /// A map (row-major, `width` × `height`, kelvin) looked up at texture coordinates (u, v): u
    /// across the columns, v down the rows (v = 0 is the top row). Bilinear, clamped at the edges.
    static TemperatureField texture(std::vector<float> map_k, int width, int height);

    /// Temperature at a hit on `mesh` (the hit's object). No exceptions (hot loop).
    double at(const SurfaceHit& hit, const TriangleMesh& mesh) const;

    /// True for a field made by `constant` (then at() is min_k() everywhere): a renderer can
    /// evaluate what depends only on the temperature, such as Planck's law per wavelength, once per
    /// object.
    bool is_constant() const { return m_kind == Kind::Constant; }

    /// Range of the field, for validation and reports.
    double min_k() const;
    double max_k() const;

private:
    enum class Kind { Constant, PerVertex, Texture };
    Kind m_kind = Kind::Constant;
    double m_constant_k = 0.0;
    std::vector<double> m_vertex_k;
    std::vector<float> m_map_k;
    int m_width = 0, m_height = 0;
};

class SkyModel;

/// Sky radiance as a grey-body ε(θ)·L_bb(λ, T(θ)) of zenith angle θ. The sky types are registered
/// by name, one file each in simulation/src/skies/ (docs/scene-format.md):
///  - uniform: ε = 1 at one temperature (or the brightness temperature of a given band radiance);
///  - clear_sky: effective emissivity ε(θ) = 1 − (1 − ε_zenith)^(1/cos θ) at the air temperature
///    (Granqvist & Hjortsberg 1981; ε_zenith from the scene or a clear-sky model of the thermal
///    module);
///  - table: band radiance vs zenith angle from a CSV (e.g. converted from MODTRAN or libRadtran),
///    turned into brightness temperatures over the band and interpolated linearly in zenith angle.
/// Below the horizon every type takes its horizon value (ε → 1 for the clear sky).
class Sky {
public:
    /// A uniform sky at 0 K (no radiance), until a scene sets one.
    Sky();
    /// The sky of `model`, a registered sky type (simulation/src/sky_model.h).
    explicit Sky(std::shared_ptr<const SkyModel> model);

    static Sky uniform(double temperature_k);
    static Sky clear_sky(double air_temperature_k, double zenith_emissivity);
    static Sky table(std::vector<double> zenith_deg, std::vector<double> band_radiance,
                     const Band& band);

    /// From the `sky:` mapping of a scene file, by its `type` (an unknown type fails at `type`
    /// listing the registered ones); `band` converts band radiances to brightness temperatures.
    static Sky from_config(const ConfigNode& node, const Band& band);

    /// Spectral radiance, W/(m²·sr·µm), seen along the world direction `direction` (pointing to the
    /// sky).
    double spectral_radiance(double wavelength_um, const Vec3& direction) const;

    /// The sky at one wavelength with Planck's law evaluated once where the temperature does not
    /// depend on the direction (uniform and clear skies): what a renderer keeps per wavelength
    /// node.
    class AtWavelength {
    public:
        /// Sky::spectral_radiance(wavelength_um, direction), W/(m²·sr·µm), to rounding (the
        /// model's per-path emissivity, e.g. the clear sky's with its logarithm taken once).
        double spectral_radiance(const Vec3& direction) const;

    private:
        friend class Sky;
        const SkyModel* m_model = nullptr;
        double m_wavelength_um = 0.0;
        bool m_isothermal = false;  ///< the temperature does not depend on the direction
        double m_blackbody = 0.0;   ///< L_bb(λ, T) when m_isothermal
    };
    /// The sky at `wavelength_um`; refers to this Sky's model, which must outlive it.
    AtWavelength at_wavelength(double wavelength_um) const;

    /// Effective emissivity and temperature at zenith angle θ given by cos θ.
    double emissivity(double cos_zenith) const;
    double temperature_k(double cos_zenith) const;

private:
    std::shared_ptr<const SkyModel> m_model;
};

/// The sun as a uniform disk of solid angle `solid_angle_sr` and spectral radiance
/// transmittance·L_bb(λ, temperature_k). Defaults: 5778 K, 6.8e-5 sr (angular radius 0.2666°).
struct Sun {
    Vec3 direction = Vec3::UnitZ();  ///< unit world vector pointing to the sun
    double temperature_k = 5778.0;
    double solid_angle_sr = 6.8e-5;
    double transmittance = 1.0;  ///< atmospheric path transmittance (grey)

    /// From the `sun:` mapping: `elevation_deg`/`azimuth_deg` (azimuth from north, clockwise toward
    /// east) or `direction`, and `temperature_k` (+ `transmittance`) or a band `radiance` in
    /// W/(m²·sr).
    static Sun from_config(const ConfigNode& node, const Band& band);

    double spectral_radiance(double wavelength_um) const;
    /// cos of the disk's angular radius: a direction d is on the disk when d·direction ≥ this.
    double cos_angular_radius() const { return 1.0 - solid_angle_sr / (2.0 * kPi); }
};

/// Default and largest allowed `max_bounces`: a safety cap, not a sampling setting.
inline constexpr int kDefaultMaxBounces = 1000;
inline constexpr int kMaxBouncesLimit = 100000;
/// Default `sampling.replicates`: independent randomised replicates per pixel, whose spread is the
/// variance channels' estimate (renderer.h). Two ("dual buffer"): every consumer of the variance
/// pools it over a region or a neighbourhood, whose degrees of freedom are then many times R − 1,
/// and each replicate keeps spp/2 points of one net (docs/simulation.md, "Why R = 2").
inline constexpr int kDefaultReplicates = 2;
/// Replicates for error bars that stand alone per pixel (Student's t with R − 1 = 15 dof: |z| > 5
/// in 0.016 % of pixels): `sampling.replicates: 16`.
inline constexpr int kPerPixelReplicates = 16;
inline constexpr int kMaxReplicates = 1024;

/// How the renderer estimates each vertex's reflected radiance (renderer.h): the plain path-traced
/// estimate, or with the reflection control variate (e0 − ε)·L_ref, exact by Kirchhoff's law, plus
/// the sampled reflection of L_in − L_ref (lower noise; docs/simulation.md).
enum class Estimator { plain, control_variate };

/// The names of scene files and the CLI: "plain", "control-variate".
std::string_view estimator_name(Estimator estimator);
/// The estimator called `name`, or nullopt if none is.
std::optional<Estimator> estimator_from_name(std::string_view name);

struct SamplingSettings {
    int samples_per_pixel = 16;
    /// Safety cap on the reflections followed after the camera's first hit. Paths end by Russian
    /// roulette (unbiased, renderer.h) long before it; a low cap truncates paths, which darkens
    /// closed reflective scenes (an all-aluminium box at 4 bounces: −87 % of L_bb).
    int max_bounces = kDefaultMaxBounces;
    std::uint64_t seed = 1;
    Estimator estimator =
        Estimator::control_variate;  ///< RenderOptions::control_variate overrides it
    /// Independently scrambled replicates of each pixel's samples (1–kMaxReplicates; 1 keeps all of
    /// a pixel's samples in one net, the lowest noise, and leaves the variance channels NaN; more
    /// give the per-pixel variance more degrees of freedom at the price of noise); a render uses
    /// replicate_count() of them.
    int replicates = kDefaultReplicates;
};

/// Replicates a render draws: min(replicates, spp) (one replicate per sample at low spp).
int replicate_count(const SamplingSettings& sampling);
/// Samples per pixel a render draws: spp rounded up to a multiple of replicate_count(), so that
/// every replicate has the same number of points (identically distributed replicate means: the
/// variance estimate's degrees of freedom are exactly replicates − 1). The EXR's `spp` records this
/// count.
int rendered_samples_per_pixel(const SamplingSettings& sampling);

/// Empty if `max_bounces` is acceptable (0–kMaxBouncesLimit), else what was expected; the one rule
/// for the scene file's sampling.max_bounces and the CLI's --max-bounces.
std::string max_bounces_problem(int max_bounces);

/// A material as used by the renderer: its pBRDF and where it came from.
struct SceneMaterial {
    std::string name;
    std::string source;  ///< file it was read from, or "inline in <scene>"
    std::shared_ptr<const materials::PolarizedBrdf> brdf;
};

struct SceneObject {
    std::string name;
    /// Index into Scene::materials: the object's material, or with per-face materials that of its
    /// first triangle.
    std::uint32_t material = 0;
    /// Per-face materials of a mesh file (the scene's `materials:` mapping): per triangle, an index
    /// into Scene::materials. Empty when the whole object is `material`.
    std::vector<std::uint32_t> triangle_materials;
    TemperatureField temperature;

    /// Index into Scene::materials of the material at triangle `primitive` (SurfaceHit::primitive).
    std::uint32_t material_at(std::uint32_t primitive) const {
        return triangle_materials.empty() ? material : triangle_materials[primitive];
    }
};

struct Scene {
    std::filesystem::path file;
    PinholeCamera camera;
    Band band;
    Sky sky;
    std::optional<Sun> sun;
    SamplingSettings sampling;
    std::vector<SceneMaterial> materials;
    std::vector<SceneObject> objects;  ///< index = RayTracer object index
    std::shared_ptr<RayTracer> tracer;
};

/// Loads a scene file. Every error names the file, line and field (unknown keys, wrong types, a
/// missing mesh or material file, an unknown material name).
Scene load_scene(const std::filesystem::path& path);
/// Same from an already parsed scene (a sweep point's overrides via ConfigNode::with_value, a
/// Python dict): relative paths resolve against the directory of `root.file()`, which becomes
/// Scene::file.
Scene load_scene(const ConfigNode& root);

}  // namespace tirpol::simulation
