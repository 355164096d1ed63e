// Experiment, not a test (not built): the noise of the region means that the glossy-paint fit on
// ball_on_snow_night compares (render_fit_test.cpp's setting, 160×128, 8 spp), over EXP_N
// measurement-like seed pairs: per residual the empirical variance against the mean of the render's
// own variance (Σ S*_var/n²) and their correlation, the S0/S1/S2 correlations within a region and
// across regions, and the measurement noise projected onto σ and n through the fit's linearisation
// (J at the truth from a 64-spp common-random-number difference) against its stated σ. To run it:
// copy it to tests/fitting/zz_region_noise_test.cpp, build tirpol_fitting_tests, and run
// EXP_N=300 build/fitting/tirpol_fitting_tests --gtest_filter='ZzExperiment.*'
// (docs/fitting.md "The ball's σ: noise or method?").
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "../render_fit_views.h"
#include "tirpol/core/source_tree.h"
#include "tirpol/fitting/render_fit.h"
#include "tirpol/simulation/renderer.h"

using namespace tirpol;
using namespace tirpol::fitting;
using namespace tirpol::test;

namespace {
int env(const char* n, int f) {
    const char* t = std::getenv(n);
    return t ? std::atoi(t) : f;
}
}  // namespace

TEST(ZzExperiment, RegionMeanNoise) {
    simulation::Scene scene = simulation::load_scene(find_config("scenes/ball_on_snow_night.yaml"));
    scene.camera = scene.camera.resized(160, 128);
    scene.sampling.samples_per_pixel = env("EXP_SPP", 8);
    const Vec3 at(0.0, 0.3, 0.3);
    const std::vector<simulation::PinholeCamera> cameras{
        camera_at(scene.camera, {0.0, -3.2, 1.1}, at),
        camera_at(scene.camera, {0.0, -2.4, 2.4}, at)};
    std::vector<std::vector<RenderFitRegion>> regions;
    std::vector<std::vector<std::uint8_t>> masks;
    for (const auto& c : cameras) {
        simulation::Scene g = scene;
        g.camera = c;
        g.sampling.samples_per_pixel = 1;
        const Image geo = simulation::render(g);
        auto r = quadrants(object_region(geo, object_named(scene, "ball"), "ball"), geo.width());
        r.push_back(object_region(geo, object_named(scene, "panel"), "panel"));
        std::vector<std::uint8_t> m(geo.width() * geo.height(), 0);
        for (auto& q : r) {
            for (auto i : q.pixels) m[i] = 1;
            std::printf("region %s %zu px\n", q.name.c_str(), q.pixels.size());
        }
        regions.push_back(r);
        masks.push_back(m);
    }
    const char* S[] = {"S0", "S1", "S2"};
    const auto values = [&](const simulation::Scene& sc, std::vector<double>& y,
                            std::vector<double>& v) {
        y.clear(), v.clear();
        for (std::size_t k = 0; k < cameras.size(); ++k) {
            simulation::Scene s = sc;
            s.camera = cameras[k];
            simulation::RenderOptions ro;
            ro.pixel_mask = &masks[k];
            const Image im = simulation::render(s, ro);
            for (const auto& r : regions[k])
                for (int c = 0; c < 3; ++c) {
                    const auto& a = im.channel(S[c]);
                    const auto& b = im.channel(std::string(S[c]) + "_var");
                    double sum = 0, sv = 0;
                    for (auto i : r.pixels) sum += a[i], sv += b[i];
                    const double n = r.pixels.size();
                    y.push_back(sum / n), v.push_back(sv / (n * n));
                }
        }
    };
    const int N = env("EXP_N", 60);
    const int m = 30;
    Eigen::MatrixXd Y(N, m), V(N, m);
    for (int s = 0; s < N; ++s) {
        std::vector<double> y, v, y1, v1;
        scene.sampling.seed = 50000 + 2 * s;
        values(scene, y, v);
        scene.sampling.seed = 50001 + 2 * s;
        values(scene, y1, v1);
        std::copy(y1.begin() + 15, y1.end(), y.begin() + 15);
        std::copy(v1.begin() + 15, v1.end(), v.begin() + 15);
        for (int j = 0; j < m; ++j) Y(s, j) = y[j], V(s, j) = v[j];
    }
    const Eigen::RowVectorXd mean = Y.colwise().mean();
    const Eigen::MatrixXd D = Y.rowwise() - mean;
    const Eigen::MatrixXd C = D.transpose() * D / (N - 1);
    const Eigen::RowVectorXd vbar = V.colwise().mean();
    std::printf("residual: empirical var / mean stated var; corr(y, v)\n");
    for (int j = 0; j < m; ++j) {
        const Eigen::VectorXd dv = V.col(j).array() - vbar(j);
        const double cyv = D.col(j).dot(dv) / std::sqrt(D.col(j).squaredNorm() * dv.squaredNorm());
        std::printf("  %2d %s ratio %.2f corr(y,v) %+.2f\n", j, S[j % 3], C(j, j) / vbar(j), cyv);
    }
    std::printf("within-region correlations (S0S1, S0S2, S1S2):\n");
    for (int r = 0; r < m / 3; ++r) {
        const int b = 3 * r;
        const auto c = [&](int i, int k) {
            return C(b + i, b + k) / std::sqrt(C(b + i, b + i) * C(b + k, b + k));
        };
        std::printf("  region %d: %+.2f %+.2f %+.2f\n", r, c(0, 1), c(0, 2), c(1, 2));
    }
    // Jacobian at truth at high spp with CRN.
    simulation::Scene hi = scene;
    hi.sampling.samples_per_pixel = env("EXP_JSPP", 64);
    hi.sampling.seed = 77;
    const std::size_t mat = [&] {
        for (std::size_t i = 0; i < scene.materials.size(); ++i)
            if (scene.materials[i].name == "glossy_black_paint") return i;
        return std::size_t{0};
    }();
    const std::vector<std::pair<MicrofacetParameter, double>> truth{
        {MicrofacetParameter::n, 1.55}, {MicrofacetParameter::sigma, 0.05}};
    const double h[2] = {0.029, 0.0038};
    Eigen::MatrixXd J(m, 2);
    for (int p = 0; p < 2; ++p) {
        std::vector<double> yp, ym, v;
        auto t = truth;
        t[p].second += h[p];
        hi.materials[mat].brdf = microfacet_with(scene, "glossy_black_paint", t);
        values(hi, yp, v);
        t = truth;
        t[p].second -= h[p];
        hi.materials[mat].brdf = microfacet_with(scene, "glossy_black_paint", t);
        values(hi, ym, v);
        for (int j = 0; j < m; ++j) J(j, p) = (yp[j] - ym[j]) / (2 * h[p]);
    }
    // Measurement + model at the same spp: total noise 2C (independent seeds); weights 1/(2 vbar).
    Eigen::VectorXd w(m);
    for (int j = 0; j < m; ++j) w(j) = 1.0 / (2 * vbar(j));
    const Eigen::MatrixXd A = (J.transpose() * w.asDiagonal() * J).inverse();
    const Eigen::MatrixXd Cdiag = Eigen::MatrixXd(C.diagonal().asDiagonal());
    const auto sandwich = [&](const Eigen::MatrixXd& Sigma) {
        return Eigen::MatrixXd(A * J.transpose() * w.asDiagonal() * (2 * Sigma) * w.asDiagonal() *
                               J * A);
    };
    const Eigen::MatrixXd full = sandwich(C), diag = sandwich(Cdiag);
    std::printf("stated sigma n %.5f sigma %.5f\n", std::sqrt(A(0, 0)), std::sqrt(A(1, 1)));
    std::printf("sandwich diag-only n %.5f sigma %.5f\n", std::sqrt(diag(0, 0)),
                std::sqrt(diag(1, 1)));
    std::printf("sandwich full C     n %.5f sigma %.5f\n", std::sqrt(full(0, 0)),
                std::sqrt(full(1, 1)));
    // GLS with block covariance (3x3 per region): its covariance
    Eigen::MatrixXd Cblock = Eigen::MatrixXd::Zero(m, m);
    for (int r = 0; r < m / 3; ++r) Cblock.block(3 * r, 3 * r, 3, 3) = C.block(3 * r, 3 * r, 3, 3);
    const Eigen::MatrixXd Wg = (2 * Cblock).inverse();
    const Eigen::MatrixXd G = (J.transpose() * Wg * J).inverse();
    std::printf("GLS block           n %.5f sigma %.5f\n", std::sqrt(G(0, 0)), std::sqrt(G(1, 1)));
    std::printf("off-block max |corr|: ");
    double mx = 0;
    for (int i = 0; i < m; ++i)
        for (int k = 0; k < m; ++k)
            if (i / 3 != k / 3) mx = std::max(mx, std::abs(C(i, k) / std::sqrt(C(i, i) * C(k, k))));
    std::printf("%.2f (N=%d: noise ~%.2f)\n", mx, N, 1 / std::sqrt(N));
    for (int i = 0; i < m; ++i)
        for (int k = i + 1; k < m; ++k)
            if (i / 3 != k / 3 && std::abs(C(i, k) / std::sqrt(C(i, i) * C(k, k))) > 0.4)
                std::printf("  pair %d %d corr %+.2f\n", i, k,
                            C(i, k) / std::sqrt(C(i, i) * C(k, k)));
    // measurement: independent seeds per view -> zero across views; model: full C.
    Eigen::MatrixXd Cmeas = C;
    for (int i = 0; i < m; ++i)
        for (int k = 0; k < m; ++k)
            if ((i < 15) != (k < 15)) Cmeas(i, k) = 0;
    const Eigen::MatrixXd mixed =
        A * J.transpose() * w.asDiagonal() * (Cmeas + C) * w.asDiagonal() * J * A;
    std::printf("sandwich meas block-diag by view + model full: n %.5f sigma %.5f\n",
                std::sqrt(mixed(0, 0)), std::sqrt(mixed(1, 1)));
    for (int K : {0, 3000}) {
        std::vector<double> y0, v0, y1, v1, y, v;
        scene.sampling.seed = 2000 + K;
        values(scene, y0, v0);
        scene.sampling.seed = 2001 + K;
        values(scene, y1, v1);
        y.assign(y0.begin(), y0.begin() + 15);
        y.insert(y.end(), y1.begin() + 15, y1.end());
        Eigen::VectorXd r(m);
        for (int j = 0; j < m; ++j) r(j) = y[j] - mean(j);
        const Eigen::VectorXd d = A * J.transpose() * w.asDiagonal() * r;
        // measurement-only linear pull in units of the full stated sigma
        std::printf("K=%5d linear dsigma %+.5f (%+.2f stated) dn %+.5f; top whitened dev:", K, d(1),
                    d(1) / std::sqrt(A(1, 1)), d(0));
        for (int j = 0; j < m; ++j)
            if (std::abs(r(j) / std::sqrt(vbar(j))) > 2.0)
                std::printf(" [%d %+.1f]", j, r(j) / std::sqrt(vbar(j)));
        std::printf("\n");
    }
    {
        const Eigen::RowVectorXd g = (A * J.transpose() * w.asDiagonal()).row(1);
        const Eigen::RowVectorXd gn = (A * J.transpose() * w.asDiagonal()).row(0);
        double s2 = 0, s4 = 0, sv = 0, n2 = 0, nv = 0;
        std::vector<double> z;
        for (int s = 0; s < N; ++s) {
            const double pr = g.dot(D.row(s)), pn = gn.dot(D.row(s));
            double var = 0, varn = 0;
            for (int j = 0; j < m; ++j)
                var += g(j) * g(j) * V(s, j), varn += gn(j) * gn(j) * V(s, j);
            s2 += pr * pr, s4 += pr * pr * pr * pr, sv += var, n2 += pn * pn, nv += varn;
            z.push_back(pr / std::sqrt(var));
        }
        std::printf(
            "sigma projection: empirical sd %.5f, sqrt(mean stated var) %.5f, ratio %.2f, kurtosis "
            "%.1f\n",
            std::sqrt(s2 / (N - 1)), std::sqrt(sv / N), std::sqrt(s2 / (N - 1) / (sv / N)),
            (s4 / N) / std::pow(s2 / N, 2));
        std::printf("n projection: empirical sd %.5f, sqrt(mean stated var) %.5f ratio %.2f\n",
                    std::sqrt(n2 / (N - 1)), std::sqrt(nv / N), std::sqrt(n2 / (N - 1) / (nv / N)));
        double zz = 0;
        int big = 0;
        for (double x : z) zz += x * x, big += std::abs(x) > 2.5;
        std::printf("sigma projection z (own var): rms %.2f, |z|>2.5: %d of %d\n",
                    std::sqrt(zz / N), big, N);
        for (int j = 0; j < m; ++j) {
            double k4 = 0;
            for (int s = 0; s < N; ++s) k4 += std::pow(D(s, j), 4);
            std::printf("  res %2d kurt %.1f ratio %.2f g*sd %+.5f\n", j,
                        k4 / N / std::pow(C(j, j), 2), C(j, j) / vbar(j),
                        g(j) * std::sqrt(C(j, j)));
        }
    }
    std::printf("J (whitened by sqrt w):\n");
    for (int j = 0; j < m; ++j)
        std::printf("  %2d %s %+8.2f %+8.2f\n", j, S[j % 3], J(j, 0) * std::sqrt(w(j)),
                    J(j, 1) * std::sqrt(w(j)));
}
