#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <numbers>

#include "stokes_row.h"
#include "stokes_uncertainty.h"
#include "tirpol/calibration/microgrid_session.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"

namespace tirpol::calibration {

namespace {
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
/// det(WᵀW)/(tr(WᵀW)/3)³ below which a cell's analyzers do not determine S: a rank-deficient W
/// gives round-off (~10⁻¹⁶), the worst valid pattern ~10⁻⁶.
constexpr double kSingularDeterminant = 1e-10;

/// Channel names of MicrogridPixelCalibration::parameter_covariance, in its order.
constexpr const char* kCovarianceChannels[10] = {"cov_w0_w0", "cov_w0_w1", "cov_w0_w2", "cov_w0_b",
                                                 "cov_w1_w1", "cov_w1_w2", "cov_w1_b",  "cov_w2_w2",
                                                 "cov_w2_b",  "cov_b_b"};
/// Index into parameter_covariance of entry (a, b) of the 4×4 symmetric matrix.
constexpr std::size_t kCovarianceIndex[4][4] = {
    {0, 1, 2, 3}, {1, 4, 5, 6}, {2, 5, 7, 8}, {3, 6, 8, 9}};

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
    if (has_pixel_covariance()) {
        const char* names[] = {"w0_std", "w1_std", "w2_std", "background_std"};
        for (std::size_t k = 0; k < 4; ++k) {
            auto& plane = image.add_channel(names[k]);
            const std::vector<float>& variance = parameter_covariance[kCovarianceIndex[k][k]];
            for (std::size_t i = 0; i < n; ++i) plane[i] = std::sqrt(variance[i]);
        }
        for (std::size_t e = 0; e < 10; ++e)
            image.set_channel(kCovarianceChannels[e], parameter_covariance[e]);
    } else if (has_uncertainties()) {
        image.set_channel("residual_std", residual_std);
        const auto p = static_cast<std::size_t>(
            std::lround(std::sqrt(static_cast<double>(unit_parameter_covariance.size()))));
        const char* names[] = {"w0_std", "w1_std", "w2_std", "background_std"};
        for (std::size_t k = 0; k < p; ++k) {
            auto& plane = image.add_channel(names[k]);
            const double unit_std = std::sqrt(unit_parameter_covariance[k * p + k]);
            for (std::size_t i = 0; i < n; ++i)
                plane[i] = static_cast<float>(residual_std[i] * unit_std);
        }
        image.attributes()["unit_parameter_covariance"] = unit_parameter_covariance;
    }
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
    if (image.has_channel("residual_std")) {
        const auto it = image.attributes().find("unit_parameter_covariance");
        if (it == image.attributes().end() ||
            !std::holds_alternative<std::vector<double>>(it->second))
            fail(
                "per-pixel calibration: channel 'residual_std' without the attribute "
                "'unit_parameter_covariance' (a list of 9 or 16 reals)");
        c.unit_parameter_covariance = std::get<std::vector<double>>(it->second);
        if (c.unit_parameter_covariance.size() != 9 && c.unit_parameter_covariance.size() != 16)
            fail(
                "per-pixel calibration: attribute 'unit_parameter_covariance' has {} values; "
                "expected 9 (3×3) or 16 (4×4)",
                c.unit_parameter_covariance.size());
        c.residual_std = image.channel("residual_std");
    }
    if (image.has_channel(kCovarianceChannels[0]))
        for (std::size_t e = 0; e < 10; ++e) {
            if (!image.has_channel(kCovarianceChannels[e]))
                fail(
                    "per-pixel calibration: channel '{}' without '{}' (the per-pixel parameter "
                    "covariance needs all 10 channels cov_w0_w0 … cov_b_b)",
                    kCovarianceChannels[0], kCovarianceChannels[e]);
            c.parameter_covariance[e] = image.channel(kCovarianceChannels[e]);
        }
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
    // Least squares with independent errors of one variance per pixel: Cov(p_i) = s_i²·(AᵀA)⁻¹,
    // s_i² = RSS_i/(J − p) (unknown without more sources than parameters).
    const Eigen::Index dof = sources - unknowns;
    if (dof > 0) {
        c.residual_std.assign(n, 0.0f);
        const Eigen::MatrixXd unit = (design.transpose() * design).inverse();
        c.unit_parameter_covariance.assign(unit.data(), unit.data() + unit.size());
    }
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
        const double rss = (design * fit - values).squaredNorm();
        sum_sq += rss;
        if (dof > 0)
            c.residual_std[i] = static_cast<float>(std::sqrt(rss / static_cast<double>(dof)));
    }
    c.fit_rms = std::sqrt(sum_sq / static_cast<double>(n * static_cast<std::size_t>(sources)));
    return c;
}

MicrogridPixelReducer::MicrogridPixelReducer(const MicrogridPixelCalibration& calibration)
    : m_width(calibration.width), m_height(calibration.height), m_units(calibration.stokes_units) {
    const std::size_t n = static_cast<std::size_t>(m_width) * static_cast<std::size_t>(m_height);
    for (std::size_t m = 0; m < 3; ++m)
        if (calibration.analysis[m].size() != n)
            fail("per-pixel calibration: its w{} plane has {} values; expected {}×{} = {}", m,
                 calibration.analysis[m].size(), m_width, m_height, n);
    if (calibration.background.size() != n)
        fail("per-pixel calibration: its background plane has {} values; expected {}×{} = {}",
             calibration.background.size(), m_width, m_height, n);
    if (!calibration.bad.empty() && calibration.bad.size() != n)
        fail("per-pixel calibration: its bad-pixel plane has {} values; expected {}×{} = {}",
             calibration.bad.size(), m_width, m_height, n);
    if (calibration.has_pixel_covariance()) {
        for (std::size_t e = 0; e < 10; ++e)
            if (calibration.parameter_covariance[e].size() != n)
                fail(
                    "per-pixel calibration: its parameter covariance plane {} has {} values; "
                    "expected {}×{} = {}",
                    kCovarianceChannels[e], calibration.parameter_covariance[e].size(), m_width,
                    m_height, n);
        m_pixel_covariance = calibration.parameter_covariance;
        m_parameters = 4;
    } else if (calibration.has_uncertainties()) {
        if (calibration.residual_std.size() != n)
            fail("per-pixel calibration: its residual_std plane has {} values; expected {}×{} = {}",
                 calibration.residual_std.size(), m_width, m_height, n);
        m_parameters = calibration.unit_parameter_covariance.size() == 16 ? 4 : 3;
        if (calibration.unit_parameter_covariance.size() !=
            static_cast<std::size_t>(m_parameters * m_parameters))
            fail("per-pixel calibration: unit_parameter_covariance has {} values; expected 9 or 16",
                 calibration.unit_parameter_covariance.size());
        m_unit_covariance = calibration.unit_parameter_covariance;
        m_residual_var.resize(n);
        for (std::size_t i = 0; i < n; ++i)
            m_residual_var[i] = calibration.residual_std[i] * calibration.residual_std[i];
    }
    const std::size_t cells = n / 4;
    for (auto& plane : m_matrix) plane.assign(cells, 0.0f);
    for (auto& plane : m_offset) plane.assign(cells, 0.0f);
    m_bad.assign(n, 0);
    const int half_width = m_width / 2;
    for (int cy = 0; cy < m_height / 2; ++cy)
        for (int cx = 0; cx < half_width; ++cx) {
            const std::size_t cell =
                static_cast<std::size_t>(cy) * static_cast<std::size_t>(half_width) +
                static_cast<std::size_t>(cx);
            // A bad pixel's row stays zero: it then adds nothing to the least squares.
            Eigen::Matrix<double, 4, 3> w = Eigen::Matrix<double, 4, 3>::Zero();
            Eigen::Vector4d background = Eigen::Vector4d::Zero();
            bool cell_has_bad = false;
            for (int k = 0; k < 4; ++k) {
                const std::size_t i = static_cast<std::size_t>(2 * cy + (k >> 1)) *
                                          static_cast<std::size_t>(m_width) +
                                      static_cast<std::size_t>(2 * cx + (k & 1));
                if (calibration.is_bad(i)) {
                    cell_has_bad = true;
                    m_bad[i] = 1;
                    continue;
                }
                for (int m = 0; m < 3; ++m)
                    w(k, m) = calibration.analysis[static_cast<std::size_t>(m)][i];
                background(k) = calibration.background[i];
            }
            if (cell_has_bad) ++m_cells_with_bad_pixels;
            // M = (WᵀW)⁻¹Wᵀ through the 3×3 normal matrix, inverted in closed form: a microgrid
            // cell's W is well conditioned (condition number ≤ 10 for a valid pattern, so ≤ 100
            // for WᵀW), and a per-cell QR made the one-shot reduction slower than the direct
            // solve it replaces. Singular: fewer than 3 good analyzers or a dead one.
            const Eigen::Matrix3d normal = w.transpose() * w;
            const double scale = normal.trace() / 3.0;
            const double determinant = normal.determinant();
            if (!(scale > 0.0) || !(determinant > kSingularDeterminant * scale * scale * scale)) {
                for (auto& plane : m_matrix) plane[cell] = kNaN;
                for (auto& plane : m_offset) plane[cell] = kNaN;
                ++m_singular_cells;
                continue;
            }
            const Eigen::Matrix<double, 3, 4> m = normal.inverse() * w.transpose();
            const Eigen::Vector3d offset = -m * background;
            for (Eigen::Index r = 0; r < 3; ++r) {
                for (Eigen::Index k = 0; k < 4; ++k)
                    m_matrix[static_cast<std::size_t>(4 * r + k)][cell] =
                        static_cast<float>(m(r, k));
                m_offset[static_cast<std::size_t>(r)][cell] = static_cast<float>(offset(r));
            }
        }
}

Image MicrogridPixelReducer::reduce(std::span<const float> mosaic,
                                    std::span<const float> mosaic_std) const {
    const std::size_t n = static_cast<std::size_t>(m_width) * static_cast<std::size_t>(m_height);
    if (mosaic.size() != n)
        fail("microgrid frame has {} values; the per-pixel calibration is {}×{} ({} values)",
             mosaic.size(), m_width, m_height, n);
    for (std::size_t i = 0; i < n; ++i)
        if (!m_bad[i] && !std::isfinite(mosaic[i]))
            fail("microgrid frame: pixel (x={}, y={}) is not finite",
                 i % static_cast<std::size_t>(m_width), i / static_cast<std::size_t>(m_width));
    if (!mosaic_std.empty()) {
        if (mosaic_std.size() != n)
            fail("microgrid frame σ has {} values; the per-pixel calibration is {}×{} ({} values)",
                 mosaic_std.size(), m_width, m_height, n);
        for (std::size_t i = 0; i < n; ++i)
            if (!m_bad[i] && !(mosaic_std[i] >= 0.0f && std::isfinite(mosaic_std[i])))
                fail("microgrid frame σ: pixel (x={}, y={}) is {}; expected a finite σ ≥ 0",
                     i % static_cast<std::size_t>(m_width), i / static_cast<std::size_t>(m_width),
                     mosaic_std[i]);
    }
    Image out(m_width / 2, m_height / 2);
    float* s[3] = {out.add_channel("S0").data(), out.add_channel("S1").data(),
                   out.add_channel("S2").data()};
    float* dolp = out.add_channel("DoLP").data();
    float* aop = out.add_channel("AoP").data();
    const auto half_width = static_cast<std::size_t>(out.width());
    const auto width = static_cast<std::size_t>(m_width);
    std::array<std::vector<float>, 4> signal;
    for (auto& row : signal) row.resize(half_width);
    for (std::size_t cy = 0; cy < static_cast<std::size_t>(out.height()); ++cy) {
        // The cell's four pixels as contiguous rows; a bad pixel reads 0 (its column of M is 0,
        // and 0 times whatever it holds, NaN included, must not reach S).
        for (std::size_t k = 0; k < 4; ++k) {
            const std::size_t first = (2 * cy + (k >> 1)) * width + (k & 1);
            const float* in = mosaic.data() + first;
            const unsigned char* bad = m_bad.data() + first;
            float* row = signal[k].data();
            for (std::size_t cx = 0; cx < half_width; ++cx)
                row[cx] = bad[2 * cx] ? 0.0f : in[2 * cx];
        }
        const std::size_t start = cy * half_width;
        for (std::size_t r = 0; r < 3; ++r) {
            const float *m0 = m_matrix[4 * r].data() + start,
                        *m1 = m_matrix[4 * r + 1].data() + start,
                        *m2 = m_matrix[4 * r + 2].data() + start,
                        *m3 = m_matrix[4 * r + 3].data() + start,
                        *offset = m_offset[r].data() + start;
            const float *i0 = signal[0].data(), *i1 = signal[1].data(), *i2 = signal[2].data(),
                        *i3 = signal[3].data();
            float* sr = s[r] + start;
            for (std::size_t cx = 0; cx < half_width; ++cx)
                sr[cx] = m0[cx] * i0[cx] + m1[cx] * i1[cx] + m2[cx] * i2[cx] + m3[cx] * i3[cx] +
                         offset[cx];
        }
        detail::finish_stokes_row(s[0] + start, s[1] + start, s[2] + start, dolp + start,
                                  aop + start, half_width, false);
    }
    if (!mosaic_std.empty() || !m_residual_var.empty() || !m_pixel_covariance[0].empty())
        add_uncertainties(out, mosaic_std);
    out.attributes()["demosaic_method"] = std::string("super-pixel");
    out.attributes()["analyzer_model"] = std::string("per-pixel");
    out.attributes()["demosaic_reference"] = std::string(
        "Powell & Gruev, Opt. Express 21(18), 21039 (2013): per-super-pixel calibration matrix");
    out.attributes()["singular_cells"] = m_singular_cells;
    out.attributes()["cells_with_bad_pixels"] = m_cells_with_bad_pixels;
    if (!m_units.empty()) write_stokes_image_header(out, {.units = m_units});
    return out;
}

void MicrogridPixelReducer::add_uncertainties(Image& out, std::span<const float> mosaic_std) const {
    const bool pixel_covariance = !m_pixel_covariance[0].empty();
    const bool calibration_error = !m_residual_var.empty() || pixel_covariance;
    write_stokes_image_header(
        out, {.std_includes = !mosaic_std.empty() && calibration_error
                                  ? "the frame's σ and the per-pixel calibration's fit error"
                              : calibration_error ? "the per-pixel calibration's fit error"
                                                  : "the frame's σ"});
    const std::vector<float>&s0 = out.channel("S0"), &s1 = out.channel("S1"),
          &s2 = out.channel("S2");
    std::vector<float>* sigma[5] = {&out.add_channel("S0_std"), &out.add_channel("S1_std"),
                                    &out.add_channel("S2_std"), &out.add_channel("DoLP_std"),
                                    &out.add_channel("AoP_std")};
    const auto p = static_cast<std::size_t>(m_parameters);
    const auto half_width = static_cast<std::size_t>(out.width());
    for (std::size_t cell = 0; cell < out.pixel_count(); ++cell) {
        const double s[3] = {s0[cell], s1[cell], s2[cell]};
        if (!std::isfinite(s[0])) {  // singular cell
            for (auto* plane : sigma) (*plane)[cell] = kNaN;
            continue;
        }
        // g = (S, 1): the sensitivity of I_k − b_k − w_k·S to the pixel's parameters (w_k, b_k).
        const double g[4] = {s[0], s[1], s[2], 1.0};
        detail::StokesCovariance c;
        const std::size_t cx = cell % half_width, cy = cell / half_width;
        for (std::size_t k = 0; k < 4; ++k) {
            const std::size_t i =
                (2 * cy + (k >> 1)) * static_cast<std::size_t>(m_width) + 2 * cx + (k & 1);
            if (m_bad[i]) continue;
            double var = 0.0;
            if (!mosaic_std.empty())
                var += static_cast<double>(mosaic_std[i]) * static_cast<double>(mosaic_std[i]);
            if (pixel_covariance) {
                for (std::size_t a = 0; a < 4; ++a)
                    for (std::size_t b = 0; b < 4; ++b)
                        var += g[a] *
                               static_cast<double>(m_pixel_covariance[kCovarianceIndex[a][b]][i]) *
                               g[b];
            } else if (calibration_error) {
                double quadratic = 0.0;
                for (std::size_t a = 0; a < p; ++a)
                    for (std::size_t b = 0; b < p; ++b)
                        quadratic += g[a] * m_unit_covariance[a * p + b] * g[b];
                var += m_residual_var[i] * quadratic;
            }
            const double m0 = m_matrix[k][cell], m1 = m_matrix[4 + k][cell],
                         m2 = m_matrix[8 + k][cell];
            c.c00 += m0 * m0 * var;
            c.c11 += m1 * m1 * var;
            c.c22 += m2 * m2 * var;
            c.c01 += m0 * m1 * var;
            c.c02 += m0 * m2 * var;
            c.c12 += m1 * m2 * var;
        }
        const detail::StokesStd sd = detail::stokes_std(s, std::hypot(s[1], s[2]), c);
        (*sigma[0])[cell] = sd.s0;
        (*sigma[1])[cell] = sd.s1;
        (*sigma[2])[cell] = sd.s2;
        (*sigma[3])[cell] = sd.dolp;
        (*sigma[4])[cell] = sd.aop_deg;
    }
}

Image reduce_microgrid_per_pixel(std::span<const float> mosaic,
                                 const MicrogridPixelCalibration& calibration) {
    const std::size_t n =
        static_cast<std::size_t>(calibration.width) * static_cast<std::size_t>(calibration.height);
    // The frame's size first: the message a caller with the wrong frame needs.
    if (mosaic.size() != n)
        fail("microgrid frame has {} values; the per-pixel calibration is {}×{} ({} values)",
             mosaic.size(), calibration.width, calibration.height, n);
    return MicrogridPixelReducer(calibration).reduce(mosaic);
}

}  // namespace tirpol::calibration
