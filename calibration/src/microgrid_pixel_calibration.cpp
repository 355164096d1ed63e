#include "tirpol/calibration/microgrid_pixel_calibration.h"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <numbers>

#include "tirpol/core/error.h"

namespace tirpol::calibration {

namespace {
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

double wrap_0_180(double angle_deg) {
    double a = std::fmod(angle_deg, 180.0);
    return a < 0.0 ? a + 180.0 : a;
}
}  // namespace

float MicrogridPixelCalibration::diattenuation(std::size_t i) const {
    return std::hypot(analysis[1][i], analysis[2][i]) / analysis[0][i];
}

float MicrogridPixelCalibration::axis_angle_deg(std::size_t i) const {
    return static_cast<float>(wrap_0_180(
        0.5 * std::atan2(static_cast<double>(analysis[2][i]), static_cast<double>(analysis[1][i])) *
        180.0 / std::numbers::pi));
}

Image MicrogridPixelCalibration::to_image() const {
    Image image(width, height);
    const std::size_t n = image.pixel_count();
    auto& t = image.add_channel("transmission");
    auto& d = image.add_channel("diattenuation");
    auto& theta = image.add_channel("axis_angle_deg");
    for (std::size_t i = 0; i < n; ++i) {
        t[i] = transmission(i);
        d[i] = diattenuation(i);
        theta[i] = axis_angle_deg(i);
    }
    image.set_channel("background", background);
    image.set_channel("w0", analysis[0]);
    image.set_channel("w1", analysis[1]);
    image.set_channel("w2", analysis[2]);
    if (!bad.empty()) image.set_channel("bad", bad);
    image.attributes()["fit_rms"] = fit_rms;
    if (!stokes_units.empty()) image.attributes()["stokes_units"] = stokes_units;
    image.attributes()["analyzer_model"] = std::string("per-pixel");
    return image;
}

MicrogridPixelCalibration MicrogridPixelCalibration::from_image(const Image& image) {
    MicrogridPixelCalibration c;
    c.width = image.width();
    c.height = image.height();
    c.analysis = {image.channel("w0"), image.channel("w1"), image.channel("w2")};
    c.background = image.channel("background");
    if (image.has_channel("bad")) c.bad = image.channel("bad");
    if (const auto it = image.attributes().find("stokes_units");
        it != image.attributes().end() && std::holds_alternative<std::string>(it->second))
        c.stokes_units = std::get<std::string>(it->second);
    if (const auto it = image.attributes().find("fit_rms");
        it != image.attributes().end() && std::holds_alternative<double>(it->second))
        c.fit_rms = std::get<double>(it->second);
    return c;
}

MicrogridPixelCalibration calibrate_microgrid_pixels(
    const std::vector<MicrogridFlatField>& flat_fields, int width, int height,
    bool fit_background) {
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    const Eigen::Index unknowns = fit_background ? 4 : 3;
    const auto sources = static_cast<Eigen::Index>(flat_fields.size());
    if (sources < unknowns)
        fail(
            "microgrid pixel calibration: {} flat field(s); expected at least {} (a reference "
            "polarizer at ≥ 3 "
            "angles{})",
            sources, unknowns, fit_background ? " and a second source radiance" : "");
    Eigen::MatrixXd design(sources, unknowns);
    for (Eigen::Index j = 0; j < sources; ++j) {
        const auto& ff = flat_fields[static_cast<std::size_t>(j)];
        if (ff.frame.size() != n)
            fail("microgrid pixel calibration: flat field {} has {} values; expected {}×{} = {}", j,
                 ff.frame.size(), width, height, n);
        if (!ff.source_stokes.allFinite())
            fail("microgrid pixel calibration: flat field {}: source Stokes is not finite", j);
        design.row(j).head<3>() = ff.source_stokes.transpose();
        if (fit_background) design(j, 3) = 1.0;
    }
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(design);
    if (qr.rank() < unknowns)
        fail(
            "microgrid pixel calibration: the sources do not span (S0, S1, S2{}): rank {} of {}; "
            "use a reference "
            "polarizer at ≥ 3 angles{}",
            fit_background ? ", background" : "", qr.rank(), unknowns,
            fit_background ? " and at least two source radiances" : "");
    const Eigen::MatrixXd pinv =
        design.completeOrthogonalDecomposition().pseudoInverse();  // unknowns × sources
    MicrogridPixelCalibration c;
    c.width = width;
    c.height = height;
    for (auto& plane : c.analysis) plane.assign(n, 0.0f);
    c.background.assign(n, 0.0f);
    Eigen::VectorXd values(sources);
    double sum_sq = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        for (Eigen::Index j = 0; j < sources; ++j) {
            const float v = flat_fields[static_cast<std::size_t>(j)].frame[i];
            if (!std::isfinite(v))
                fail("microgrid pixel calibration: flat field {}: pixel (x={}, y={}) is not finite",
                     j, i % static_cast<std::size_t>(width), i / static_cast<std::size_t>(width));
            values(j) = v;
        }
        const Eigen::VectorXd fit = pinv * values;
        for (std::size_t k = 0; k < 3; ++k)
            c.analysis[k][i] = static_cast<float>(fit(static_cast<Eigen::Index>(k)));
        if (fit_background) c.background[i] = static_cast<float>(fit(3));
        sum_sq += (design * fit - values).squaredNorm();
    }
    c.fit_rms = std::sqrt(sum_sq / static_cast<double>(n * static_cast<std::size_t>(sources)));
    return c;
}

Image reduce_microgrid_per_pixel(std::span<const float> mosaic,
                                 const MicrogridPixelCalibration& calibration) {
    const int width = calibration.width, height = calibration.height;
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    if (mosaic.size() != n)
        fail("microgrid frame has {} values; the per-pixel calibration is {}×{} ({} values)",
             mosaic.size(), width, height, n);
    if (!calibration.bad.empty() && calibration.bad.size() != n)
        fail("per-pixel calibration: its bad-pixel plane has {} values; expected {}×{} = {}",
             calibration.bad.size(), width, height, n);
    for (std::size_t i = 0; i < n; ++i)
        if (!calibration.is_bad(i) && !std::isfinite(mosaic[i]))
            fail("microgrid frame: pixel (x={}, y={}) is not finite",
                 i % static_cast<std::size_t>(width), i / static_cast<std::size_t>(width));
    Image out(width / 2, height / 2);
    auto& s0 = out.add_channel("S0");
    auto& s1 = out.add_channel("S1");
    auto& s2 = out.add_channel("S2");
    auto& dolp = out.add_channel("DoLP");
    auto& aop = out.add_channel("AoP");
    int singular = 0, with_bad = 0;
    for (int cy = 0; cy < out.height(); ++cy)
        for (int cx = 0; cx < out.width(); ++cx) {
            // A bad pixel's row stays zero: it then adds nothing to the least squares.
            Eigen::Matrix<double, 4, 3> w = Eigen::Matrix<double, 4, 3>::Zero();
            Eigen::Vector4d signal = Eigen::Vector4d::Zero();
            bool cell_has_bad = false;
            for (int k = 0; k < 4; ++k) {
                const std::size_t i =
                    static_cast<std::size_t>(2 * cy + (k >> 1)) * static_cast<std::size_t>(width) +
                    static_cast<std::size_t>(2 * cx + (k & 1));
                if (calibration.is_bad(i)) {
                    cell_has_bad = true;
                    continue;
                }
                for (int m = 0; m < 3; ++m)
                    w(k, m) = calibration.analysis[static_cast<std::size_t>(m)][i];
                signal(k) = static_cast<double>(mosaic[i]) - calibration.background[i];
            }
            if (cell_has_bad) ++with_bad;
            const std::size_t o = out.index(cx, cy);
            const Eigen::ColPivHouseholderQR<Eigen::Matrix<double, 4, 3>> qr(w);
            if (qr.rank() < 3) {
                s0[o] = s1[o] = s2[o] = dolp[o] = aop[o] = kNaN;
                ++singular;
                continue;
            }
            const Eigen::Vector3d s = qr.solve(signal);
            s0[o] = static_cast<float>(s(0));
            s1[o] = static_cast<float>(s(1));
            s2[o] = static_cast<float>(s(2));
            dolp[o] = s(0) > 0.0 ? static_cast<float>(std::hypot(s(1), s(2)) / s(0)) : kNaN;
            aop[o] = static_cast<float>(
                wrap_0_180(0.5 * std::atan2(s(2), s(1)) * 180.0 / std::numbers::pi));
        }
    out.attributes()["demosaic_method"] = std::string("super-pixel");
    out.attributes()["analyzer_model"] = std::string("per-pixel");
    out.attributes()["demosaic_reference"] = std::string(
        "Powell & Gruev, Opt. Express 21(18), 21039 (2013): per-super-pixel calibration matrix");
    out.attributes()["singular_cells"] = singular;
    out.attributes()["cells_with_bad_pixels"] = with_bad;
    if (!calibration.stokes_units.empty()) out.attributes()["units"] = calibration.stokes_units;
    return out;
}

}  // namespace tirpol::calibration
