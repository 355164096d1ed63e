// The microgrid camera's twin: render → DoFP sensor served over GigE Vision → flat-field sessions
// (blackbody open, then behind the reference polarizer on the simulated stage) → per-pixel
// calibration → scene session → per-super-pixel reduction → comparison with the rendered truth.

#include "tirpol/twin/dofp_twin.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>

#include "regions.h"
#include "tirpol/calibration/microgrid_session.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/session.h"
#include "tirpol/core/source_tree.h"
#include "tirpol/simulation/render_output.h"
#include "tirpol/simulation/renderer.h"
#include "tirpol/simulation/scene.h"

namespace tirpol::twin {

namespace {

namespace fs = std::filesystem;
using acquisition::CapturePlan;

/// Adds the wall time of a stage to the result when it goes out of scope.
class StageClock {
public:
    StageClock(DofpTwinResult& r, std::string name, std::string& current)
        : m_result(r), m_name(std::move(name)), m_start(std::chrono::steady_clock::now()) {
        current = m_name;
    }
    ~StageClock() {
        m_result.seconds[m_name] =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
    }
    StageClock(const StageClock&) = delete;
    StageClock& operator=(const StageClock&) = delete;

private:
    DofpTwinResult& m_result;
    std::string m_name;
    std::chrono::steady_clock::time_point m_start;
};

/// A flat-field session of microgrid_flat_field.h's conventions: the open blackbody at
/// `open_blackbody_k` (operator-placed references; none when empty), then the blackbody at
/// `polarizer_blackbody_k` behind the reference polarizer at every angle.
CapturePlan flat_field_plan(const DofpTwinOptions& o, const std::vector<double>& open_blackbody_k,
                            double polarizer_blackbody_k) {
    CapturePlan plan;
    plan.angles_deg = o.reference_angles_deg;
    plan.frames_per_angle = o.flat_frames;
    plan.settle_s = 0.05;
    if (!open_blackbody_k.empty()) {
        acquisition::ReferenceSpec open;
        open.kind = RecordKind::Blackbody;
        open.temperatures_k = open_blackbody_k;
        open.frames = o.flat_frames;
        plan.references.push_back(open);
    }
    nlohmann::json repeat = nlohmann::json::object();
    repeat["repeat"] = 0;
    repeat["blackbody_temperature_k"] = polarizer_blackbody_k;
    nlohmann::json flat = nlohmann::json::object();
    flat["reference_polarizer_axis_offset_deg"] = 0.0;
    flat["reference_polarizer_diattenuation"] = o.reference.diattenuation();
    flat["polarizer_repeats"] = nlohmann::json::array({repeat});
    plan.metadata["polarizer_in_beam"] = false;
    plan.metadata["microgrid_flat_field"] = flat;
    return plan;
}

/// The NUC's open-blackbody set-points: the brightness temperatures of the scene's darkest and
/// brightest pixels, 2 K outside, as a user brackets what the camera will see.
std::vector<double> open_blackbody_setpoints(const Image& truth, const Band& band) {
    double lo = INFINITY, hi = 0.0;
    for (float s0 : truth.channel("S0"))
        if (std::isfinite(s0) && s0 > 0.0f) {
            lo = std::min(lo, static_cast<double>(s0));
            hi = std::max(hi, static_cast<double>(s0));
        }
    if (!(hi > 0.0)) fail("the truth render has no positive S0");
    return {band.brightness_temperature(lo) - 2.0, band.brightness_temperature(hi) + 2.0};
}

struct SuperPixelStokes {
    double s[3] = {0, 0, 0};
    double dolp() const { return std::hypot(s[1], s[2]) / s[0]; }
};

/// The footprint truth of one super-pixel: the mean of its four pixels' rendered Stokes.
SuperPixelStokes truth_cell(const Image& truth, int cx, int cy) {
    SuperPixelStokes t;
    const char* names[3] = {"S0", "S1", "S2"};
    for (int c = 0; c < 3; ++c) {
        const auto& plane = truth.channel(names[c]);
        for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx)
                t.s[c] +=
                    0.25 *
                    plane[static_cast<std::size_t>((2 * cy + dy) * truth.width() + 2 * cx + dx)];
    }
    return t;
}

/// What this microgrid camera measures in one super-pixel without noise and with its analyzers
/// known exactly: each of the four pixels sees its own rendered Stokes through its planted analysis
/// vector, I_p = w_p·S_p, and the cell is reduced by W⁺ of those four vectors. It differs from
/// truth_cell by the IFOV error alone (the four analyzers see four places).
SuperPixelStokes exact_dofp_cell(const Image& truth, const simulation::DofpSensor& sensor, int cx,
                                 int cy) {
    Eigen::Matrix<double, 4, 3> w;
    Eigen::Vector4d intensity;
    const char* names[3] = {"S0", "S1", "S2"};
    for (int p = 0; p < 4; ++p) {
        const int x = 2 * cx + p % 2, y = 2 * cy + p / 2;
        const std::size_t i = static_cast<std::size_t>(y * truth.width() + x);
        const auto analysis = sensor.pixels().analysis(i);
        intensity[p] = 0.0;
        for (int c = 0; c < 3; ++c) {
            w(p, c) = analysis[static_cast<std::size_t>(c)];
            intensity[p] += w(p, c) * truth.channel(names[c])[i];
        }
    }
    const Eigen::Vector3d s = (w.transpose() * w).ldlt().solve(w.transpose() * intensity);
    return {{s[0], s[1], s[2]}};
}

SuperPixelStokes measured_cell(const Image& stokes, int cx, int cy) {
    SuperPixelStokes m;
    const char* names[3] = {"S0", "S1", "S2"};
    for (int c = 0; c < 3; ++c)
        m.s[c] = stokes.channel(names[c])[static_cast<std::size_t>(cy * stokes.width() + cx)];
    return m;
}

double wrapped_axis_difference_deg(double a, double b) {
    double d = a - b;
    d -= 180.0 * std::round(d / 180.0);
    return d;
}

DofpParameterRecovery parameter_recovery(const calibration::MicrogridPixelCalibration& fitted,
                                         const simulation::DofpSensor& sensor) {
    const simulation::DofpPixels& planted = sensor.pixels();
    DofpParameterRecovery r;
    double mean_g = 0.0, mean_d = 0.0;
    const std::size_t n = planted.axis_deg.size();
    for (std::size_t i = 0; i < n; ++i) {
        mean_g += planted.analysis(i)[0] / static_cast<double>(n);
        mean_d += planted.diattenuation[i] / static_cast<double>(n);
    }
    double sq_axis = 0.0, sq_d = 0.0, sq_g = 0.0, sq_axis_spread = 0.0, sq_d_spread = 0.0,
           sq_g_spread = 0.0;
    for (int y = 0; y < sensor.height(); ++y)
        for (int x = 0; x < sensor.width(); ++x) {
            const std::size_t i = static_cast<std::size_t>(y * sensor.width() + x);
            const double planted_g = planted.analysis(i)[0];
            sq_axis_spread += std::pow(
                wrapped_axis_difference_deg(planted.axis_deg[i], sensor.nominal_angle_deg(x, y)),
                2);
            sq_d_spread += std::pow(planted.diattenuation[i] - mean_d, 2);
            sq_g_spread += std::pow(planted_g / mean_g - 1.0, 2);
            if (fitted.is_bad(i)) continue;
            sq_axis += std::pow(
                wrapped_axis_difference_deg(fitted.axis_angle_deg(i), planted.axis_deg[i]), 2);
            sq_d += std::pow(fitted.diattenuation(i) - planted.diattenuation[i], 2);
            sq_g += std::pow(fitted.analysis[0][i] / planted_g - 1.0, 2);
            ++r.pixels;
        }
    if (r.pixels == 0) fail("every pixel was marked bad");
    const double good = static_cast<double>(r.pixels), all = static_cast<double>(n);
    r.axis_rms_deg = std::sqrt(sq_axis / good);
    r.diattenuation_rms = std::sqrt(sq_d / good);
    r.gain_rel_rms = std::sqrt(sq_g / good);
    r.planted_axis_spread_deg = std::sqrt(sq_axis_spread / all);
    r.planted_diattenuation_spread = std::sqrt(sq_d_spread / all);
    r.planted_gain_rel_spread = std::sqrt(sq_g_spread / all);
    return r;
}

/// The mean of component c of `diffs` over its standard error (the scatter of the values).
double mean_pull(const std::vector<std::array<double, 3>>& diffs, int c) {
    const std::size_t k = static_cast<std::size_t>(c);
    const double n = static_cast<double>(diffs.size());
    double mean = 0.0;
    for (const auto& d : diffs) mean += d[k] / n;
    double ss = 0.0;
    for (const auto& d : diffs) ss += (d[k] - mean) * (d[k] - mean);
    return mean / std::sqrt(ss / (n - 1.0) / n);
}

/// Regions: the interior rectangle of every object the camera sees, as whole super-pixels.
void compare_regions(DofpTwinResult& r, const simulation::Scene& scene, const Image& truth,
                     const simulation::DofpSensor& sensor, const Image& per_pixel,
                     const Image& nuc_only) {
    double sq_pull = 0.0, sq_pull_nuc = 0.0, sq_dolp = 0.0, sq_dolp_nuc = 0.0;
    int pulls = 0, dolp_cells = 0;
    for (std::size_t k = 0; k < scene.objects.size(); ++k) {
        const auto rect = object_rect(truth, k);
        if (!rect) continue;
        const int cx0 = (rect->x + 1) / 2, cx1 = (rect->x + rect->width) / 2;  // [cx0, cx1)
        const int cy0 = (rect->y + 1) / 2, cy1 = (rect->y + rect->height) / 2;
        std::vector<std::array<double, 3>> diffs, diffs_nuc;
        DofpRegionCheck region;
        region.name = scene.objects[k].name;
        for (int cy = cy0; cy < cy1; ++cy)
            for (int cx = cx0; cx < cx1; ++cx) {
                const SuperPixelStokes m = measured_cell(per_pixel, cx, cy);
                if (!std::isfinite(m.s[0])) continue;  // a cell without three good analyzers
                const SuperPixelStokes t = exact_dofp_cell(truth, sensor, cx, cy);
                const SuperPixelStokes footprint = truth_cell(truth, cx, cy);
                const SuperPixelStokes nuc = measured_cell(nuc_only, cx, cy);
                diffs.push_back({m.s[0] - t.s[0], m.s[1] - t.s[1], m.s[2] - t.s[2]});
                diffs_nuc.push_back({nuc.s[0] - t.s[0], nuc.s[1] - t.s[1], nuc.s[2] - t.s[2]});
                for (int c = 0; c < 3; ++c) {
                    region.measured[c] += m.s[c];
                    region.truth[c] += t.s[c];
                    region.footprint_truth[c] += footprint.s[c];
                }
                sq_dolp += std::pow(m.dolp() - t.dolp(), 2);
                sq_dolp_nuc += std::pow(nuc.dolp() - t.dolp(), 2);
                ++dolp_cells;
            }
        // The scatter needs a few cells to estimate σ; smaller regions are left out.
        if (diffs.size() < 6) continue;
        region.super_pixels = static_cast<int>(diffs.size());
        const double n = static_cast<double>(diffs.size());
        for (int c = 0; c < 3; ++c) {
            region.measured[c] /= n;
            region.truth[c] /= n;
            region.footprint_truth[c] /= n;
            const double pull = mean_pull(diffs, c);
            sq_pull += pull * pull;
            sq_pull_nuc += std::pow(mean_pull(diffs_nuc, c), 2);
            region.sigma[c] = (region.measured[c] - region.truth[c]) / pull;
            r.pull_max_abs = std::max(r.pull_max_abs, std::abs(pull));
            ++pulls;
        }
        r.regions.push_back(region);
    }
    if (pulls == 0) fail("no region of ≥ 6 super-pixels: the image is too small");
    r.pull_rms = std::sqrt(sq_pull / pulls);
    r.pull_rms_nuc_only = std::sqrt(sq_pull_nuc / pulls);
    r.dolp_rms_per_pixel = std::sqrt(sq_dolp / dolp_cells);
    r.dolp_rms_nuc_only = std::sqrt(sq_dolp_nuc / dolp_cells);
}

void run_chain(const DofpTwinOptions& o, DofpTwinResult& r, std::string& stage) {
    simulation::Scene scene = simulation::load_scene(
        o.scene_file.empty() ? find_config("scenes/panels_night.yaml") : o.scene_file);
    scene.camera = scene.camera.resized(o.width, o.height);
    scene.sampling.samples_per_pixel = o.spp;
    fs::create_directories(o.out_dir);

    Image truth;
    {
        StageClock t(r, "render truth", stage);
        simulation::RenderOptions render_options;
        render_options.threads = o.threads;
        truth = simulation::render(scene, render_options);
        simulation::write_render_outputs(o.out_dir / "truth", "scene", truth);
        r.truth_exr = o.out_dir / "truth" / "scene.exr";
    }

    stage = "instrument set-up (stage on a pty, GigE Vision microgrid camera)";
    TwinWorld world(simulation::DofpSensor(o.sensor, o.width, o.height, scene.band), o.reference,
                    scene.band);
    world.set_scene(truth);
    TwinInstrument instrument(world, o.stage_protocol, o.gige, o.genicam_xml);
    r.camera_transport = instrument.camera_transport();
    r.stage_description = instrument.stage_description();

    {
        StageClock t(r, "acquire flat fields", stage);
        const std::vector<double> open_k = open_blackbody_setpoints(truth, scene.band);
        for (std::size_t k = 0; k < o.polarizer_blackbody_k.size(); ++k) {
            const fs::path dir = o.out_dir / "sessions" / fmt::format("flat{}", k);
            world.set_flat_field_backdrop(o.polarizer_blackbody_k[k]);
            instrument.acquire(flat_field_plan(o, k == 0 ? open_k : std::vector<double>{},
                                               o.polarizer_blackbody_k[k]),
                               dir);
            r.flat_sessions.push_back(dir);
        }
        world.set_flat_field_backdrop(std::nullopt);
    }
    {
        StageClock t(r, "acquire scene", stage);
        CapturePlan plan;
        plan.angles_deg = {0.0};  // a microgrid camera needs no polarizer turn
        plan.frames_per_angle = o.scene_frames;
        plan.settle_s = 0.05;
        plan.metadata["polarizer_in_beam"] = false;
        r.scene_session = o.out_dir / "sessions" / "scene";
        const acquisition::CaptureSummary summary = instrument.acquire(plan, r.scene_session);
        r.frame_rate_hz = summary.delivered_frame_rate_hz.value_or(0.0);
        r.pixel_format = read_session(r.scene_session).camera.pixel_format;
    }

    calibration::MicrogridFlatFieldCalibration cal;
    {
        StageClock t(r, "calibrate microgrid", stage);
        cal = calibration::calibrate_microgrid_sessions(r.flat_sessions, scene.band);
        r.calibration_exr = o.out_dir / "calibration" / "pixcal.exr";
        fs::create_directories(r.calibration_exr.parent_path());
        write_exr(r.calibration_exr, cal.pixels.to_image());
        r.bad_pixels = cal.bad_count();
        r.parameters = parameter_recovery(cal.pixels, *world.dofp());
    }
    {
        StageClock t(r, "reduce and compare", stage);
        calibration::MicrogridSessionOptions per_pixel;
        per_pixel.pixel_calibration = cal.pixels;
        const Image measured = calibration::reduce_microgrid_session(r.scene_session, per_pixel);
        r.measured_exr = o.out_dir / "measured" / "scene_stokes.exr";
        fs::create_directories(r.measured_exr.parent_path());
        write_exr(r.measured_exr, measured);
        calibration::MicrogridSessionOptions nuc;
        nuc.pixel_calibration = cal.nuc_only;
        const Image nuc_only = calibration::reduce_microgrid_session(r.scene_session, nuc);
        compare_regions(r, scene, truth, *world.dofp(), measured, nuc_only);
    }
}

}  // namespace

DofpTwinResult run_dofp_twin(const DofpTwinOptions& options) {
    DofpTwinResult result;
    std::string stage = "set-up";
    try {
        run_chain(options, result, stage);
    } catch (const std::exception& e) {
        fail("DoFP twin, {} stage: {}", stage, e.what());
    }
    return result;
}

std::string dofp_twin_summary(const DofpTwinResult& r) {
    std::string s;
    s += fmt::format("camera: {} ({}, {:.1f} frames/s delivered)\n", r.camera_transport,
                     r.pixel_format, r.frame_rate_hz);
    s += fmt::format("stage:  {}\n", r.stage_description);
    const DofpParameterRecovery& p = r.parameters;
    s += fmt::format(
        "per-pixel analyzers over {} good pixels ({} marked bad), fitted − planted RMS:\n"
        "  axis          {:.4f}° (planted spread about the nominal pattern {:.3f}°)\n"
        "  diattenuation {:.5f} (planted σ {:.4f})\n"
        "  gain          {:.5f} relative (planted σ {:.4f})\n",
        p.pixels, r.bad_pixels, p.axis_rms_deg, p.planted_axis_spread_deg, p.diattenuation_rms,
        p.planted_diattenuation_spread, p.gain_rel_rms, p.planted_gain_rel_spread);
    s += fmt::format(
        "DoLP RMS error over the regions: {:.5f} per-pixel calibration, {:.5f} NUC "
        "with ideal analyzers\n",
        r.dolp_rms_per_pixel, r.dolp_rms_nuc_only);
    s += "regions, measured − truth (W/(m² sr)), its pull, and the IFOV error (exact DoFP − "
         "footprint mean) in the same σ, per Stokes component:\n";
    for (const DofpRegionCheck& g : r.regions) {
        s += fmt::format("  {:<28} {:4d} cells", g.name, g.super_pixels);
        for (int c = 0; c < 3; ++c)
            s += fmt::format("  S{} {:+.4f} ({:+.2f}; IFOV {:+.2f})", c, g.measured[c] - g.truth[c],
                             g.pull(c), (g.truth[c] - g.footprint_truth[c]) / g.sigma[c]);
        s += "\n";
    }
    s += fmt::format(
        "pulls: RMS {:.2f}, max |pull| {:.2f} over {} values (NUC with ideal analyzers: RMS "
        "{:.2f})\n",
        r.pull_rms, r.pull_max_abs, 3 * r.regions.size(), r.pull_rms_nuc_only);
    for (const auto& [name, sec] : r.seconds) s += fmt::format("  {:<22} {:.1f} s\n", name, sec);
    return s;
}

}  // namespace tirpol::twin
