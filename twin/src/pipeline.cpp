// The digital twin's chain: render → acquire (GigE camera + pty stage) → calibrate → reduce →
// extract emissivity → fit → render with the fitted paint → compare.

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdlib>

#include "paint_render_fit.h"
#include "regions.h"
#include "tirpol/acquisition/capture_plan.h"
#include "tirpol/calibration/calibration_chain.h"
#include "tirpol/calibration/emissivity_extraction.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/core/source_tree.h"
#include "tirpol/core/utc_time.h"
#include "tirpol/core/utf8.h"
#include "tirpol/fitting/fit_run.h"
#include "tirpol/fitting/microfacet_fit.h"
#include "tirpol/materials/emissivity.h"
#include "tirpol/materials/material.h"
#include "tirpol/materials/microfacet.h"
#include "tirpol/report/comparison_report.h"
#include "tirpol/simulation/render_output.h"
#include "tirpol/simulation/renderer.h"
#include "tirpol/twin/instrument.h"
#include "tirpol/twin/twin.h"

namespace tirpol::twin {

namespace fs = std::filesystem;

namespace {

/// Emissivity tables are evaluated at this wavelength for the fit: the paint's index is constant
/// over the 8–14 µm band, so the band-integrated ε equals ε at any wavelength in it.
constexpr double kFitWavelengthUm = 10.0;
constexpr double kContactThermometerStdK = 0.2;  ///< contact thermometer

/// Times one stage of the chain and names it for error messages.
class StageTimer {
public:
    StageTimer(TwinResult& r, std::string name, std::string& current)
        : m_r(r), m_name(std::move(name)) {
        current = m_name;
    }
    ~StageTimer() {
        m_r.seconds[m_name] =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
    }

private:
    TwinResult& m_r;
    std::string m_name;
    std::chrono::steady_clock::time_point m_start = std::chrono::steady_clock::now();
};

std::vector<TwinView> default_views(const simulation::Scene& scene) {
    const Vec3 p = scene.camera.position();
    TwinView first;
    for (int i = 0; i < 3; ++i) first.position[i] = p[i];
    // Look where the scene's camera looks: a point 6 m along its optical axis.
    const Vec3 target = p + 6.0 * Vec3(scene.camera.world_from_camera().col(2));
    for (int i = 0; i < 3; ++i) first.look_at[i] = target[i];
    // Two higher positions on the same side: the flat black paint panel (tilted 30° toward the
    // camera) is seen ≈ 58°, 41° and 25° off its normal.
    TwinView mid = first, high = first;
    mid.position[1] = -5.0, mid.position[2] = 3.4;
    high.position[1] = -3.8, high.position[2] = 4.6;
    return {first, mid, high};
}

simulation::PinholeCamera view_camera(const simulation::PinholeCamera& base, const TwinView& v) {
    const Vec3 pos(v.position[0], v.position[1], v.position[2]),
        at(v.look_at[0], v.look_at[1], v.look_at[2]);
    return simulation::PinholeCamera(
        base.width(), base.height(), base.intrinsics(), pos,
        simulation::PinholeCamera::look_at(pos, at, Vec3(0.0, 0.0, 1.0)));
}

std::string reference_yaml(const std::vector<double>& temperatures_k, double angle_deg,
                           int frames) {
    std::string temps;
    for (double t : temperatures_k) temps += fmt::format("{}{:.2f}", temps.empty() ? "" : ", ", t);
    return fmt::format("  - {{kind: blackbody, temperatures_k: [{}], frames: {}, angle_deg: {}}}\n",
                       temps, frames, angle_deg);
}

/// Writes a capture plan as a person would for `tirpol acquire`, and loads it the same way.
acquisition::CapturePlan write_plan(const fs::path& path, const std::string& references,
                                    bool polarizer_in_beam, const std::string& site, int frames) {
    std::string yaml = fmt::format(
        "# Capture plan of the digital twin (tirpol demo); run it with `tirpol acquire` on a real "
        "instrument.\n"
        "angles_deg: [0, 45, 90, 135]\nframes_per_angle: {}\nsettle_s: 0.02\nframe_timeout_s: 5\n",
        frames);
    if (!references.empty()) yaml += "references:\n" + references;
    yaml += fmt::format("metadata: {{site: \"{}\", polarizer_in_beam: {}}}\n", site,
                        polarizer_in_beam ? "true" : "false");
    write_file_atomic(path, yaml);
    return acquisition::CapturePlan::load(path);
}

/// Standard error of the ROI mean from the per-pixel σ channel (pixels' noise independent):
/// √(Σσ²)/n.
double rect_standard_error(const Image& image, const std::string& sigma_channel,
                           const calibration::PixelRect& rect) {
    const auto& sigma = image.channel(sigma_channel);
    const auto variance =
        calibration::region_mean_of(rect, "twin", sigma_channel, [&](int x, int y) {
            const double v = sigma[image.index(x, y)];
            return v * v;
        });
    return std::sqrt(variance.mean / static_cast<double>(variance.n));
}

/// Standard error of the ROI mean of a − b from the scatter of a − b over the ROI.
double rect_difference_standard_error(const Image& a, const Image& b, const std::string& channel,
                                      const calibration::PixelRect& rect) {
    const auto &ca = a.channel(channel), &cb = b.channel(channel);
    const auto difference = calibration::region_mean_of(
        rect, "twin", channel, [&](int x, int y) { return ca[a.index(x, y)] - cb[b.index(x, y)]; });
    if (difference.n < 2) fail("twin: fewer than 2 finite {} pixels in the rectangle", channel);
    return difference.standard_error;
}

/// The twin's measurement inherits the Monte Carlo noise of the truth render it observes, which its
/// *_std channels (temporal noise) do not hold; the fresh render has its own. Both enter the z
/// statistic, so the simulation's variance channels carry both (S_k_var += truth S_k_var) and the
/// written simulated EXR holds the σ the report used: `tirpol compare` on the files repeats it.
void add_truth_render_noise(Image& simulated, const Image& truth) {
    for (const char* s : {"S0", "S1", "S2"}) {
        auto& var = simulated.channel(std::string(s) + "_var");
        const auto& truth_var = truth.channel(std::string(s) + "_var");
        for (std::size_t i = 0; i < var.size(); ++i)
            if (std::isfinite(truth_var[i])) var[i] += truth_var[i];
    }
    write_stokes_image_header(
        simulated,
        {.variance_note = "S0_var..S2_var include the Monte Carlo variance of the twin's truth "
                          "render"});
}

report::Region rect_region(const std::string& name, const calibration::PixelRect& r) {
    // Region polygons are in pixel-centre coordinates (docs/report.md): the rectangle's pixels have
    // centres x .. x + width − 1.
    const double x0 = r.x, y0 = r.y, x1 = r.x + r.width - 1, y1 = r.y + r.height - 1;
    return {name, {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, "twin: " + name};
}

/// What the chain's stages hand on to each other, in the order they fill it.
struct Chain {
    Chain(const TwinOptions& options, TwinResult& r, std::string& current_stage,
          simulation::Scene s)
        : opt(options),
          result(r),
          stage(current_stage),
          out(options.out_dir),
          sessions(out / "sessions"),
          scene(std::move(s)) {}

    const TwinOptions& opt;
    TwinResult& result;
    std::string& stage;  ///< the last stage started, for error messages
    fs::path out, sessions;
    simulation::Scene scene;
    std::vector<TwinView> views;
    simulation::RenderOptions render_options;
    std::size_t target = 0, reflector = 0;
    std::uint32_t target_material = 0;
    std::vector<simulation::PinholeCamera> cameras;  ///< the field camera in each view
    std::vector<Image> truth;                        ///< renders of the truth, per view
    calibration::ChainProducts calibrated;  ///< the calibrations; reduced Stokes (.stokes) per view
    fitting::EmissivityDataset dataset{"twin", kFitWavelengthUm, {}};
    Image simulated;  ///< the render with the fitted paint, view 0
};

/// 1. The truth: the paper's nine panels under a clear night sky, from every view, through the
///    field camera as it is — a realistic lens, and not quite where the user set it up.
void render_truth(Chain& c) {
    const simulation::PinholeCamera field_lens = with_realistic_lens(c.scene.camera);
    StageTimer t(c.result, "render truth", c.stage);
    for (std::size_t v = 0; v < c.views.size(); ++v) {
        c.cameras.push_back(with_pose_error(view_camera(field_lens, c.views[v])));
        simulation::Scene s = c.scene;
        if (c.opt.perturb_truth) c.opt.perturb_truth(s);
        s.camera = c.cameras.back();
        // The truth's Monte Carlo variance enters the measured σ, so it takes the replicates of a
        // well-estimated variance, not the scene default's 2 (a 1-dof estimate per pixel).
        s.sampling.replicates = simulation::kPerPixelReplicates;
        c.truth.push_back(simulation::render(s, c.render_options));
        simulation::write_render_outputs(c.out / "truth", fmt::format("view{}", v), c.truth.back());
    }
}

/// 2. The field instrument plays the scene; three kinds of session, as on a real night.
void acquire_sessions(Chain& c, TwinWorld& world, TwinInstrument& instrument) {
    StageTimer t(c.result, "acquire", c.stage);
    world.set_scene(c.truth.front());
    // The set-points bracket what the camera will see (the truth renders through the instrument),
    // as a user would choose them from the scene's expected radiances.
    c.result.blackbody = blackbody_setpoints(c.truth, world.sensor(), c.scene.band);
    // Laboratory: blackbody at three temperatures, polarizer out of the beam (radiometric
    // calibration).
    const auto lab = write_plan(
        c.sessions / "lab_plan.yaml",
        reference_yaml(c.result.blackbody.radiometric_k, 0.0, 2 * c.opt.frames_per_angle), false,
        "digital twin: laboratory", c.opt.frames_per_angle);
    instrument.acquire(lab, c.sessions / "lab");
    c.result.sessions.push_back(c.sessions / "lab");
    for (std::size_t v = 0; v < c.views.size(); ++v) {
        // Field: the first view also takes the blackbody through the polarizer at each angle
        // (polarimetric calibration); later views reuse that night's calibration.
        std::string refs;
        if (v == 0)
            for (double a : {0.0, 45.0, 90.0, 135.0})
                refs += reference_yaml(c.result.blackbody.polarimetric_k, a,
                                       2 * c.opt.frames_per_angle);
        const std::string name = fmt::format("view{}", v);
        const auto plan = write_plan(c.sessions / (name + "_plan.yaml"), refs, true,
                                     "digital twin: field, " + name, c.opt.frames_per_angle);
        world.set_scene(c.truth[v]);
        instrument.acquire(plan, c.sessions / name);
        c.result.sessions.push_back(c.sessions / name);
    }
}

/// The camera's geometry, recovered as in the field: lens from filmed checkerboard frames, pose
/// from the surveyed panel corners.
void recover_geometry(Chain& c, TwinWorld& world) {
    StageTimer t(c.result, "camera geometry", c.stage);
    CameraGeometryOptions go;
    go.threads = c.opt.threads;
    c.result.camera = recover_camera_geometry(c.scene, c.cameras.front(),
                                              view_camera(c.scene.camera, c.views.front()), world,
                                              c.out / "camera", go);
}

/// 3. Calibration and reduction to measured Stokes (the calibration chain's steps up to the
/// reduction).
void calibrate_and_reduce(Chain& c, const TwinWorld& world) {
    StageTimer t(c.result, "calibrate and reduce", c.stage);
    calibration::ChainInputs in;
    in.band = c.scene.band;
    in.blackbody_sessions = {c.sessions / "lab"};
    in.polarimetric_session = c.sessions / "view0";
    // The user has the polarizer's datasheet but no known polarized source: its extinction ratio
    // enters the analyzer model (an ideal analyzer scales S1, S2 by (ER − 1)/(ER + 1), −0.5 % at
    // 400:1 — beyond the noise where the reflectors mirror a polarized sky).
    in.datasheet = calibration::DatasheetAnalyzer{world.sensor().analyzer.extinction_ratio, {}};
    for (std::size_t v = 0; v < c.views.size(); ++v)
        in.scene_sessions.push_back(c.sessions / fmt::format("view{}", v));
    c.calibrated = calibration::run_calibration_chain(in);
    for (std::size_t v = 0; v < c.views.size(); ++v)
        write_exr(c.out / "measured" / fmt::format("view{}_stokes.exr", v), c.calibrated.stokes[v]);
    c.result.measured_exr = c.out / "measured" / "view0_stokes.exr";
}

/// Target Stokes, measured vs truth (first view). The uncertainty of the ROI mean is the scatter
/// of measured − truth over the ROI / √n: it holds the temporal noise (the *_std channels) and the
/// per-pixel errors of the radiometric and polarimetric calibrations, which those channels leave
/// out.
void check_target_stokes(Chain& c) {
    const auto target_rect0 = object_rect(c.truth.front(), c.target);
    if (!target_rect0) fail("twin: the target '{}' is not visible in view 0", c.opt.target);
    for (int k = 0; k < 3; ++k) {
        const std::string s = fmt::format("S{}", k);
        c.result.target_stokes.measured[k] =
            calibration::region_mean(c.calibrated.stokes.front(), s, *target_rect0, "twin").mean;
        c.result.target_stokes.truth[k] =
            calibration::region_mean(c.truth.front(), s, *target_rect0, "twin").mean;
        c.result.target_stokes.std_error[k] = rect_difference_standard_error(
            c.calibrated.stokes.front(), c.truth.front(), s, *target_rect0);
        c.result.target_stokes.std_error_temporal[k] =
            rect_standard_error(c.calibrated.stokes.front(), s + "_std", *target_rect0);
    }
}

/// The eq-17 regions of view v: the target with its contact temperature, the reflector with its
/// datasheet emissivity toward the camera and its contact temperature (its single-scattering facet
/// model reflects only 0.87 at 58°, so its own emission is not negligible at night).
calibration::EmissivityRois emissivity_rois(const Chain& c, std::size_t v) {
    const auto rect = object_rect(c.truth[v], c.target);
    const auto refl = object_rect(c.truth[v], c.reflector);
    if (!rect || !refl) fail("twin: view {}: target or reflector not visible", v);
    const auto mean_of = [&](const char* channel, const calibration::PixelRect& r) {
        return calibration::region_mean(c.truth[v], channel, r, "twin").mean;
    };
    calibration::EmissivityRois rois;
    const auto* reflector_brdf =
        c.scene.materials[c.scene.objects[c.reflector].material].brdf.get();
    rois.reflector = {*refl,
                      materials::directional_emissivity(
                          *reflector_brdf, std::cos(deg_to_rad(mean_of("view_zenith_deg", *refl))),
                          kFitWavelengthUm)(0),
                      0.0, mean_of("temperature_k", *refl), kContactThermometerStdK};
    calibration::EmissivityTarget et;
    et.name = fmt::format("{}_view{}", c.opt.target, v);
    et.rect = *rect;
    et.view_angle_deg = mean_of("view_zenith_deg", *rect);
    et.temperature_k = mean_of("temperature_k", *rect);
    et.temperature_std_k = kContactThermometerStdK;
    rois.targets.push_back(et);
    return rois;
}

/// 4. Polarized emissivity of the target in each view (the chain's eq 17 step) in the
/// plane-of-emission
///    frame, next to eq 17 on the truth render (a perfect instrument) and the paint's table.
void extract_target_emissivity(Chain& c) {
    const auto* true_brdf = c.scene.materials[c.target_material].brdf.get();
    StageTimer t(c.result, "extract emissivity", c.stage);
    calibration::ChainInputs in;
    in.band = c.scene.band;
    for (std::size_t v = 0; v < c.views.size(); ++v) in.rois.push_back(emissivity_rois(c, v));
    c.calibrated = calibration::run_calibration_chain(in, std::move(c.calibrated));
    for (std::size_t v = 0; v < c.views.size(); ++v) {
        const calibration::EmissivityRois& rois = in.rois[v];
        const calibration::EmissivityTarget& et = rois.targets.front();
        // Image frame → plane of emission: the p direction lies at ψ in the image; a frame with its
        // 0° axis along s (ψ − 90°) gives ε_S1 < 0 for p-polarized emission.
        const double psi = plane_of_emission_angle(c.truth[v], c.cameras[v], et.rect);
        const auto e = in_plane_of_emission(c.calibrated.emissivity[v].front(), psi);
        // The same extraction on the truth render: what eq 17 itself gives with a perfect
        // instrument.
        const auto m = in_plane_of_emission(
            calibration::extract_emissivity(c.truth[v], rois, c.scene.band).front(), psi);
        TwinEmissivity te;
        te.view_angle_deg = et.view_angle_deg;
        te.eps_s0 = e.eps_s0;
        te.eps_s0_std = e.eps_s0_std;
        te.eps_s1 = e.eps_s1;
        te.eps_s1_std = e.eps_s1_std;
        te.method_s0 = m.eps_s0;
        te.method_s0_std = m.eps_s0_std;
        te.method_s1 = m.eps_s1;
        te.method_s1_std = m.eps_s1_std;
        const StokesVector truth_eps = materials::directional_emissivity(
            *true_brdf, std::cos(deg_to_rad(te.view_angle_deg)), kFitWavelengthUm);
        te.true_s0 = truth_eps(0);
        te.true_s1 = truth_eps(1);
        c.result.emissivity.push_back(te);
        c.dataset.samples.push_back(
            {te.view_angle_deg, te.eps_s0, te.eps_s0_std, te.eps_s1, te.eps_s1_std, et.name});
    }
    write_file_atomic(c.out / "fit" / "emissivity.csv", fitting::emissivity_csv({c.dataset}));
}

/// 5. Fit the paint: n and σ free; k and ρ_D held at the library's values (three view angles do
///    not separate a small k from n, docs/fitting.md) and the other parameters at their defaults.
void fit_paint(Chain& c) {
    const auto* micro = dynamic_cast<const materials::MicrofacetBrdf*>(
        c.scene.materials[c.target_material].brdf.get());
    if (!micro) fail("twin: the target material is not a micro-facet model");
    const materials::ShellTargetParameters<double> true_params = micro->at(kFitWavelengthUm);
    StageTimer t(c.result, "fit", c.stage);
    fitting::MicrofacetFitOptions fo;
    fo.starts = 8;
    using P = fitting::MicrofacetParameter;
    for (const auto& [p, value] :
         {std::pair{P::k, true_params.k}, std::pair{P::rho_d, true_params.rho_d}}) {
        auto& setting = fo.parameters[static_cast<std::size_t>(p)];
        setting.initial = value;
        setting.fixed = true;
    }
    const fitting::MicrofacetFitProblem problem({c.dataset}, fo);
    const fitting::MicrofacetFitResult fit = problem.solve();
    c.result.fitted_material = c.out / "fit" / "flat_black_paint_fitted.yaml";
    const fitting::FitProvenance provenance{{(c.out / "fit" / "emissivity.csv").string()},
                                            utc_now_iso8601(),
                                            "tirpol demo (digital twin)"};
    write_file_atomic(c.result.fitted_material,
                      fitting::fitted_material_yaml("flat_black_paint_fitted", fit, provenance));
    write_file_atomic(c.out / "fit" / "fit.json",
                      json_text(fitting::fit_report_json(fit, problem.datasets(), provenance), 2));
    c.result.reduced_chi2 = fit.reduced_chi2;
    c.result.dof = fit.dof;
    const auto truths = fitting::fit_order_values(true_params);
    for (std::size_t i = 0; i < fit.parameters.size(); ++i) {
        const auto& p = fit.parameters[i];
        c.result.parameters.push_back({p.name, truths[i], p.value, p.std_uncertainty, p.fixed});
    }
}

/// 5b. The same paint fitted through the renderer (no uniform-downwelling assumption), starting
/// from
///     eq 17's result; written beside it in fit/paint_fits.txt. The fit renders view 0 through the
///     recovered camera and views 1 and 2 through their true cameras (the twin recovers the
///     geometry of view 0 only).
void fit_paint_by_rendering(Chain& c) {
    StageTimer t(c.result, "fit through the renderer", c.stage);
    PaintRenderFitInputs in;
    in.scene = &c.scene;
    in.cameras = c.cameras;
    in.cameras.front() = c.result.camera.camera();
    in.measured = &c.calibrated.stokes;
    in.truth = &c.truth;
    in.target_object = c.target;
    in.target_material = c.target_material;
    for (const auto& p : c.result.parameters) {
        if (p.name == "n") in.initial_n = p.fitted, in.true_n = p.truth;
        if (p.name == "sigma") in.initial_sigma = p.fitted, in.true_sigma = p.truth;
    }
    in.seed = c.scene.sampling.seed + 2;  // neither the truth's seed nor the re-render's
    // Four times the truth's samples: only the regions' pixels are traced, so σ_render stays well
    // below the measurement's for little time.
    in.samples_per_pixel = 4 * c.opt.spp;
    in.threads = c.opt.threads;
    c.result.render_fit = fit_paint_through_renderer(in);
    c.result.fit_comparison = c.out / "fit" / "paint_fits.txt";
    write_file_atomic(c.result.fit_comparison, paint_fit_comparison(c.result));
}

/// 6. The same scene rendered with the fitted paint (fresh samples) through the recovered camera —
///    the simulation to compare, on the measured pixel grid.
void render_fitted(Chain& c) {
    StageTimer t(c.result, "render fitted", c.stage);
    const materials::Material fitted = materials::load_material(c.result.fitted_material);
    simulation::Scene s = c.scene;
    s.camera = c.result.camera.camera();
    if (c.opt.render_fitted_target) s.materials[c.target_material].brdf = fitted.brdf;
    s.sampling.seed = c.scene.sampling.seed + 1;
    c.simulated = simulation::render(s, c.render_options);
    add_truth_render_noise(c.simulated, c.truth.front());
    simulation::write_render_outputs(c.out / "simulated", "view0_fitted", c.simulated);
    c.result.simulated_exr = c.out / "simulated" / "view0_fitted.exr";
}

/// 7. The comparison report, one region per panel.
void compare_and_report(Chain& c) {
    StageTimer t(c.result, "compare", c.stage);
    report::CompareOptions co;
    // Rendered through the recovered camera: registration by the camera model, no warp.
    co.registration = report::RegistrationMethod::CameraModel;
    co.camera_model = c.result.camera.lens;
    co.camera_model_name = c.result.camera.lens_file.string();
    co.measured_name = c.result.measured_exr.string();
    co.simulated_name = c.result.simulated_exr.string();
    report::RegionSet regions;
    for (std::size_t i = 0; i < c.scene.objects.size(); ++i) {
        const std::string& name = c.scene.objects[i].name;
        if (name.rfind("panel_", 0) != 0) continue;
        if (const auto r = object_rect(c.truth.front(), i))
            regions.regions.push_back(rect_region(name.substr(6), *r));
    }
    co.regions = regions;
    co.design = c.opt.report_design;
    // The regions as a file and the equivalent command, so the report can be repeated from files.
    c.result.report_regions = c.out / "report_regions.yaml";
    write_file_atomic(c.result.report_regions, report::regions_yaml(regions));
    co.provenance.tool_version = c.opt.tool_version;
    co.provenance.command_line = fmt::format(
        "tirpol compare --measured {} --simulated {} --rois {} --camera {} --false-alarm {} "
        "--power {} -o {} (run in-process by `tirpol demo`)",
        c.result.measured_exr.string(), c.result.simulated_exr.string(),
        c.result.report_regions.string(), c.result.camera.lens_file.string(),
        co.design.false_alarm_per_region, co.design.power, (c.out / "report").string());
    co.provenance.inputs.push_back(
        report::describe_input("measured", c.result.measured_exr, &c.calibrated.stokes.front()));
    co.provenance.inputs.push_back(
        report::describe_input("simulated", c.result.simulated_exr, &c.simulated));
    co.provenance.inputs.push_back(report::describe_input("regions", c.result.report_regions));
    co.provenance.inputs.push_back(
        report::describe_input("camera model", c.result.camera.lens_file));
    co.provenance.inputs.push_back(report::describe_input(
        "paint fits: eq 17 and through the renderer", c.result.fit_comparison));
    const report::CompareResult cr =
        write_comparison_report(c.calibrated.stokes.front(), c.simulated, co, c.out / "report");
    c.result.report_html = cr.html;
    c.result.registration = cr.registration;
    for (const auto& r : cr.regions)
        c.result.regions.push_back(
            {r.name, r.pixel_count, {r.verdicts.s0, r.verdicts.s1, r.verdicts.s2}, r.verdict});
    c.result.report_summary = report::summary_paragraph(cr);
    if (cr.calibration_range)
        c.result.calibration_outside_fraction = cr.calibration_range->outside_fraction;
}

void run_chain(const TwinOptions& opt, TwinResult& result, std::string& stage) {
    Chain c(opt, result, stage,
            simulation::load_scene(opt.scene_file.empty() ? find_config("scenes/panels_night.yaml")
                                                          : opt.scene_file));
    fs::create_directories(c.out);
    c.scene.camera = c.scene.camera.resized(opt.width, opt.height);
    c.scene.sampling.samples_per_pixel = opt.spp;
    if (opt.seed) c.scene.sampling.seed = *opt.seed;
    c.views = opt.views.empty() ? default_views(c.scene) : opt.views;
    c.render_options.threads = opt.threads;
    c.target = object_index(c.scene, opt.target);
    c.reflector = object_index(c.scene, opt.reflector);
    c.target_material = c.scene.objects[c.target].material;

    render_truth(c);
    const double air_k = c.scene.sky.temperature_k(1.0);  // clear sky: the air temperature
    simulation::SensorModel sensor = twin_sensor(c.scene.band, air_k);
    if (opt.seed) sensor.seed = *opt.seed;
    TwinWorld world(sensor, c.scene.band, opt.width, opt.height);
    stage = "instrument set-up (stage on a pty, GigE Vision camera)";
    TwinInstrument instrument(world, opt.stage_protocol, opt.gige);
    result.camera_transport = instrument.camera_transport();
    result.stage_description = instrument.stage_description();
    acquire_sessions(c, world, instrument);
    recover_geometry(c, world);
    calibrate_and_reduce(c, world);
    check_target_stokes(c);
    extract_target_emissivity(c);
    fit_paint(c);
    fit_paint_by_rendering(c);
    render_fitted(c);
    compare_and_report(c);
}

}  // namespace

TwinResult run_twin(const TwinOptions& options) {
    TwinResult result;
    std::string stage = "set-up";  // the last stage started
    try {
        run_chain(options, result, stage);
    } catch (const std::exception& e) {
        fail("digital twin, {} stage: {}", stage, e.what());
    }
    return result;
}

}  // namespace tirpol::twin
