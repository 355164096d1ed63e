#include "microgrid_single_pass.h"

#include <vector>

#include "microgrid_newton_row.h"
#include "stokes_attributes.h"
#include "stokes_row.h"
#include "tirpol/core/interrupt_signals.h"

namespace tirpol::calibration::detail {

namespace {

/// The output channels as row pointers, and what every row adds to the unrealizable count.
struct StokesOutput {
    Image image;
    float *s0, *s1, *s2, *dolp, *aop;
    std::size_t unrealizable = 0;

    StokesOutput(int width, int height) : image(width, height) {
        s0 = image.add_channel("S0").data();
        s1 = image.add_channel("S1").data();
        s2 = image.add_channel("S2").data();
        dolp = image.add_channel("DoLP").data();
        aop = image.add_channel("AoP").data();
    }
    void finish_row(std::size_t start, std::size_t count, bool project) {
        unrealizable += finish_stokes_row(s0 + start, s1 + start, s2 + start, dolp + start,
                                          aop + start, count, project);
    }
};

/// One mosaic row as float with one mirrored pixel on each side: padded[x + 1] = row[x],
/// padded[0] = row[1], padded[width + 1] = row[width − 2] (the mirror of demosaic_microgrid).
template <typename T>
void pad_row(const T* row, int width, float* padded) {
    for (int x = 0; x < width; ++x) padded[x + 1] = static_cast<float>(row[x]);
    padded[0] = padded[2];
    padded[width + 1] = padded[width - 1];
}

int mirror_row(int y, int height) {
    if (y < 0) return -y;
    if (y >= height) return 2 * (height - 1) - y;
    return y;
}

/// One Stokes component of one row from three padded mosaic rows (up, current, down) and the
/// per-x coefficients of the own, horizontal, vertical and diagonal analyzer. Also built for AVX2,
/// picked at load time where the CPU has it (the same arithmetic, 8 lanes instead of 4).
TIRPOL_MICROGRID_CLONES
void bilinear_stokes_row(const float* __restrict u, const float* __restrict c,
                         const float* __restrict d, const float* __restrict k_own,
                         const float* __restrict k_h, const float* __restrict k_v,
                         const float* __restrict k_d, float offset, float* __restrict out,
                         std::size_t width) {
    for (std::size_t x = 0; x < width; ++x) {
        const float own = c[x + 1];
        const float horizontal = 0.5f * (c[x] + c[x + 2]);
        const float vertical = 0.5f * (u[x + 1] + d[x + 1]);
        const float diagonal = 0.25f * (u[x] + u[x + 2] + d[x] + d[x + 2]);
        out[x] =
            k_own[x] * own + k_h[x] * horizontal + k_v[x] * vertical + k_d[x] * diagonal + offset;
    }
}

/// One Stokes component of one row from the four analyzers' values at each x (own, horizontal,
/// vertical and diagonal neighbour's) and their per-x coefficients. AVX2 clone as above.
TIRPOL_MICROGRID_CLONES
void role_stokes_row(const float* __restrict own, const float* __restrict horizontal,
                     const float* __restrict vertical, const float* __restrict diagonal,
                     const float* __restrict k_own, const float* __restrict k_h,
                     const float* __restrict k_v, const float* __restrict k_d, float offset,
                     float* __restrict out, std::size_t width) {
    for (std::size_t x = 0; x < width; ++x)
        out[x] = k_own[x] * own[x] + k_h[x] * horizontal[x] + k_v[x] * vertical[x] +
                 k_d[x] * diagonal[x] + offset;
}

/// coefficient[parity_y][r][role][x]: the matrix entry of row r for the analyzer in `role` (0 own,
/// 1 horizontal, 2 vertical, 3 diagonal neighbour) at column x of a row of that parity; which cell
/// each role is depends on the parities of x and y only.
using RoleCoefficients = std::array<std::array<std::array<std::vector<float>, 4>, 3>, 2>;

RoleCoefficients role_coefficients(const CellStokesMatrix& cm, std::size_t width) {
    RoleCoefficients coefficient;
    for (std::size_t py = 0; py < 2; ++py)
        for (std::size_t r = 0; r < 3; ++r)
            for (std::size_t role = 0; role < 4; ++role) {
                auto& k = coefficient[py][r][role];
                k.resize(width);
                for (std::size_t x = 0; x < width; ++x)
                    k[x] = cm.matrix[r][(py * 2 + (x & 1)) ^ role];
            }
    return coefficient;
}

/// Bilinear (Ratliff et al. 2009, as demosaic_microgrid): at pixel x of a row the own analyzer is
/// the pixel, the horizontal neighbour's the mean of left and right, the vertical one's the mean of
/// up and down, the diagonal one's the mean of the four corners; which cell each of them is depends
/// on the parities of x and y only, so per row parity the matrix is laid out per x (even and odd
/// columns alternate) and the inner loop is a plain multiply-add over arrays.
template <typename T>
void bilinear(const T* mosaic, int width, int height, const CellStokesMatrix& cm,
              const ReductionOptions& options, StokesOutput& out) {
    const auto w = static_cast<std::size_t>(width);
    const RoleCoefficients coefficient = role_coefficients(cm, w);
    std::vector<float> up(w + 2), cur(w + 2), down(w + 2);
    for (int y = 0; y < height; ++y) {
        throw_if_cancelled(options.cancel, "microgrid reduction");
        pad_row(mosaic + static_cast<std::size_t>(mirror_row(y - 1, height)) * w, width, up.data());
        pad_row(mosaic + static_cast<std::size_t>(y) * w, width, cur.data());
        pad_row(mosaic + static_cast<std::size_t>(mirror_row(y + 1, height)) * w, width,
                down.data());
        const auto& k = coefficient[static_cast<std::size_t>(y & 1)];
        const std::size_t start = static_cast<std::size_t>(y) * w;
        float* s[3] = {out.s0 + start, out.s1 + start, out.s2 + start};
        for (std::size_t r = 0; r < 3; ++r)
            bilinear_stokes_row(up.data(), cur.data(), down.data(), k[r][0].data(), k[r][1].data(),
                                k[r][2].data(), k[r][3].data(), cm.offset[r], s[r], w);
        out.finish_row(start, w, options.project_to_realizable);
    }
}

/// Super-pixel: each 2×2 cell is one sample of the four analyzers.
template <typename T>
void super_pixel(const T* mosaic, int width, int height, const CellStokesMatrix& cm,
                 const ReductionOptions& options, StokesOutput& out) {
    const auto w = static_cast<std::size_t>(width);
    const std::size_t half_w = w / 2;
    for (int cy = 0; cy < height / 2; ++cy) {
        throw_if_cancelled(options.cancel, "microgrid reduction");
        const T* row0 = mosaic + static_cast<std::size_t>(2 * cy) * w;
        const T* row1 = row0 + w;
        const std::size_t start = static_cast<std::size_t>(cy) * half_w;
        float* s[3] = {out.s0 + start, out.s1 + start, out.s2 + start};
        for (std::size_t r = 0; r < 3; ++r) {
            // Local copies: the output pointers could alias the matrix as far as the compiler
            // knows, which would keep it from vectorising.
            const float m0 = cm.matrix[r][0], m1 = cm.matrix[r][1], m2 = cm.matrix[r][2],
                        m3 = cm.matrix[r][3], offset = cm.offset[r];
            float* sr = s[r];
            for (std::size_t cx = 0; cx < half_w; ++cx)
                sr[cx] = m0 * static_cast<float>(row0[2 * cx]) +
                         m1 * static_cast<float>(row0[2 * cx + 1]) +
                         m2 * static_cast<float>(row1[2 * cx]) +
                         m3 * static_cast<float>(row1[2 * cx + 1]) + offset;
        }
        out.finish_row(start, half_w, options.project_to_realizable);
    }
}

/// Newton (microgrid_newton_row.h, as demosaic_microgrid): per row the three neighbours'
/// estimates, then the matrix by role as for bilinear; no four-plane image.
template <typename T>
void newton(const T* mosaic, int width, int height, const CellStokesMatrix& cm,
            const ReductionOptions& options, StokesOutput& out) {
    const auto w = static_cast<std::size_t>(width);
    const RoleCoefficients coefficient = role_coefficients(cm, w);
    const PaddedMosaic padded(mosaic, width, height);
    const float epsilon = newton_epsilon(mosaic, w * static_cast<std::size_t>(height));
    std::vector<float> horizontal(w), vertical(w), diagonal(w);
    for (int y = 0; y < height; ++y) {
        throw_if_cancelled(options.cancel, "microgrid reduction");
        newton_row(padded, y, w, epsilon, horizontal.data(), vertical.data(), diagonal.data());
        const auto& k = coefficient[static_cast<std::size_t>(y & 1)];
        const std::size_t start = static_cast<std::size_t>(y) * w;
        float* s[3] = {out.s0 + start, out.s1 + start, out.s2 + start};
        for (std::size_t r = 0; r < 3; ++r)
            role_stokes_row(padded.row(y, 0), horizontal.data(), vertical.data(), diagonal.data(),
                            k[r][0].data(), k[r][1].data(), k[r][2].data(), k[r][3].data(),
                            cm.offset[r], s[r], w);
        out.finish_row(start, w, options.project_to_realizable);
    }
}

template <typename T>
Image reduce(std::span<const T> mosaic, int width, int height, const MicrogridPattern& pattern,
             const AnalyzerModel& model, DemosaicMethod method, const ReductionOptions& options) {
    const CellStokesMatrix cm = cell_stokes_matrix(model, pattern);
    const bool half = method == DemosaicMethod::SuperPixel;
    StokesOutput out(half ? width / 2 : width, half ? height / 2 : height);
    switch (method) {
        case DemosaicMethod::SuperPixel:
            super_pixel(mosaic.data(), width, height, cm, options, out);
            break;
        case DemosaicMethod::Bilinear:
            bilinear(mosaic.data(), width, height, cm, options, out);
            break;
        case DemosaicMethod::Newton:
            newton(mosaic.data(), width, height, cm, options, out);
            break;
    }
    write_stokes_attributes(out.image, model, model.data_reduction_matrix(), options,
                            static_cast<int>(out.unrealizable), false);
    return std::move(out.image);
}

}  // namespace

CellStokesMatrix cell_stokes_matrix(const AnalyzerModel& model, const MicrogridPattern& pattern) {
    const Eigen::Matrix3Xd drm = model.data_reduction_matrix();
    CellStokesMatrix cm;
    std::array<double, 3> offset{};
    for (std::size_t k = 0; k < model.positions.size(); ++k) {
        const AnalyzerPosition& position = model.positions[k];
        const auto cell = static_cast<std::size_t>(pattern.cell_of(position.nominal_angle_deg));
        for (std::size_t r = 0; r < 3; ++r) {
            // reduce_stokes: S = W⁺·(I − b)/t per position.
            const double column = drm(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k)) /
                                  position.relative_transmission;
            cm.matrix[r][cell] = static_cast<float>(column);
            offset[r] -= column * position.background;
        }
    }
    for (std::size_t r = 0; r < 3; ++r) cm.offset[r] = static_cast<float>(offset[r]);
    return cm;
}

Image reduce_microgrid_single_pass(std::span<const float> mosaic, int width, int height,
                                   const MicrogridPattern& pattern, const AnalyzerModel& model,
                                   DemosaicMethod method, const ReductionOptions& options) {
    return reduce(mosaic, width, height, pattern, model, method, options);
}

Image reduce_microgrid_single_pass(std::span<const std::uint16_t> mosaic, int width, int height,
                                   const MicrogridPattern& pattern, const AnalyzerModel& model,
                                   DemosaicMethod method, const ReductionOptions& options) {
    return reduce(mosaic, width, height, pattern, model, method, options);
}

}  // namespace tirpol::calibration::detail
