// The twin's truth camera (realistic lens, pose error) and its recovery through the field
// procedure: geometric calibration from filmed checkerboard frames, pose from surveyed control
// points.

#include <fmt/format.h>

#include <random>

#include "tirpol/calibration/geometric_calibration.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/source_tree.h"
#include "tirpol/simulation/heated_board.h"
#include "tirpol/simulation/renderer.h"
#include "tirpol/twin/twin.h"

namespace tirpol::twin {

namespace fs = std::filesystem;

simulation::PinholeCamera with_realistic_lens(const simulation::PinholeCamera& nominal) {
    simulation::CameraIntrinsics k = nominal.intrinsics();
    k.fy = 1.004 * k.fx;
    k.cx += 0.031 * nominal.width();
    k.cy -= 0.024 * nominal.height();
    k.k1 = -0.30, k.k2 = 0.12, k.p1 = 0.0008, k.p2 = -0.0005, k.k3 = 0.0;
    return simulation::PinholeCamera(nominal.width(), nominal.height(), k, nominal.position(),
                                     nominal.world_from_camera());
}

simulation::PinholeCamera with_pose_error(const simulation::PinholeCamera& camera) {
    const Mat3 rotation =
        Eigen::AngleAxisd(deg_to_rad(0.8), Vec3(0.4, 1.0, 0.3).normalized()).toRotationMatrix();
    return simulation::PinholeCamera(camera.width(), camera.height(), camera.intrinsics(),
                                     camera.position() + Vec3(0.04, -0.06, 0.03),
                                     rotation * camera.world_from_camera());
}

namespace {

double rotation_between_deg(const CameraPose& a, const CameraPose& b) {
    return rad_to_deg(
        Eigen::AngleAxisd(a.camera_from_world * b.camera_from_world.transpose()).angle());
}

/// Frames of the heated checkerboard through the truth lens, as the camera's detector delivers them
/// (counts EXRs, polarizer out of the beam), one per board_calibration_views() view.
std::vector<fs::path> film_board(const simulation::PinholeCamera& truth, const TwinWorld& world,
                                 const fs::path& dir, const CameraGeometryOptions& options,
                                 std::string& target) {
    fs::create_directories(dir);
    write_camera_model(dir / "truth_lens.yaml", truth.lens_model());
    const simulation::HeatedBoard board;
    target = board.target();
    const std::string object = board.write(dir);
    simulation::RenderOptions render_options;
    render_options.threads = options.threads;
    std::vector<fs::path> frames;
    const auto views = simulation::board_calibration_views(
        options.board_views, truth.lens_model().fx, truth.width(), options.board_max_tilt_deg,
        options.board_roll_spread_deg);
    for (std::size_t i = 0; i < views.size(); ++i) {
        const fs::path scene_file = dir / fmt::format("board_view{:02}.yaml", i);
        write_file_atomic(
            scene_file, simulation::board_scene(object, find_config("materials"), "truth_lens.yaml",
                                                views[i].position, views[i].look_at, views[i].up,
                                                options.board_spp));
        const Image stokes = simulation::render(simulation::load_scene(scene_file), render_options);
        Image frame(stokes.width(), stokes.height());
        frame.set_channel("counts", world.sensor_frame(stokes, 0.0, false, 1'000'000 + i));
        frames.push_back(dir / fmt::format("board{:02}.exr", i));
        write_exr(frames.back(), frame);
    }
    return frames;
}

/// The corners of every `panel_*` object (surveyed world coordinates) and where `truth` sees them,
/// with `sigma_px` of pick noise, as the control-point CSV `tirpol calibrate pose` reads.
std::string control_points_csv(const simulation::Scene& field,
                               const simulation::PinholeCamera& truth, double sigma_px) {
    std::mt19937_64 rng(14);
    std::normal_distribution<double> pick(0.0, sigma_px);
    std::string csv =
        "# panel corners: surveyed world coordinates (m) and their pixels (OpenCV convention)\n"
        "name,x_m,y_m,z_m,u_px,v_px\n";
    for (std::size_t i = 0; i < field.objects.size(); ++i) {
        if (field.objects[i].name.rfind("panel_", 0) != 0) continue;
        const auto& corners = field.tracer->mesh(static_cast<std::uint32_t>(i)).positions;
        for (std::size_t c = 0; c < corners.size(); ++c) {
            const auto px = truth.project(corners[c]);
            if (!px || px->x() < 1.0 || px->y() < 1.0 || px->x() > truth.width() - 1 ||
                px->y() > truth.height() - 1)
                continue;
            // Corner-origin pixels of the renderer → OpenCV's centre-origin convention.
            const Vec2 pixel = *px - Vec2(0.5, 0.5) + Vec2(pick(rng), pick(rng));
            csv +=
                fmt::format("{}_{},{:.6f},{:.6f},{:.6f},{:.4f},{:.4f}\n", field.objects[i].name, c,
                            corners[c].x(), corners[c].y(), corners[c].z(), pixel.x(), pixel.y());
        }
    }
    return csv;
}

}  // namespace

CameraGeometryRecovery recover_camera_geometry(const simulation::Scene& field,
                                               const simulation::PinholeCamera& truth,
                                               const simulation::PinholeCamera& nominal,
                                               const TwinWorld& world, const fs::path& dir,
                                               const CameraGeometryOptions& options) {
    CameraGeometryRecovery r;
    r.true_lens = truth.lens_model();
    r.true_pose = truth.pose();
    r.nominal_pose = nominal.pose();

    // `tirpol calibrate geometric board*.exr --target checkerboard:9x6:0.06 -o camera.yaml`
    std::string target;
    const std::vector<fs::path> frames = film_board(truth, world, dir / "board", options, target);
    r.board_frames = static_cast<int>(frames.size());
    calibration::GeometricCalibrationOptions go;
    go.fix_k3 = options.fix_k3;
    const auto geometric = calibration::calibrate_geometric_frames(
        frames, calibration::CalibrationTarget::parse(target), go);
    r.lens = geometric.model;
    r.lens_parameter_names = geometric.parameter_names;
    r.lens_file = dir / "camera.yaml";
    write_camera_model(r.lens_file, r.lens);

    // `tirpol calibrate pose --camera camera.yaml --points control_points.csv -o pose.yaml`
    r.control_points_file = dir / "control_points.csv";
    write_file_atomic(r.control_points_file,
                      control_points_csv(field, truth, options.pick_sigma_px));
    const auto points = calibration::read_control_points(r.control_points_file);
    r.control_points = static_cast<int>(points.size());
    r.pose = calibration::estimate_pose(r.lens, points).pose;
    r.pose_file = dir / "pose.yaml";
    write_camera_pose(r.pose_file, r.pose);

    r.rotation_error_deg = rotation_between_deg(r.pose, r.true_pose);
    r.position_error_m = (r.pose.position_m() - r.true_pose.position_m()).norm();
    r.nominal_rotation_error_deg = rotation_between_deg(r.nominal_pose, r.true_pose);
    r.nominal_position_error_m = (r.nominal_pose.position_m() - r.true_pose.position_m()).norm();
    return r;
}

}  // namespace tirpol::twin
