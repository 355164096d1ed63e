// Detection + calibration of 20 views of a 640×512 checkerboard (target: ≤ 2 s on 2 cores),
// against a copy of the same 20 frames measured in the same run (the cost of touching the input).
// Frames are rasterised through a distorted LWIR lens (core CameraModel) with 4×4 supersampled
// edges, optical blur ignored; a 14-bit pedestal, 60 counts of contrast and inverted polarity as in
// the field.

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstring>
#include <random>

#include "../tests/support/truth_lens.h"
#include "tirpol/calibration/geometric_calibration.h"

namespace {

using namespace tirpol;
using namespace tirpol::calibration;

constexpr int kW = 640, kH = 512, kViews = 20, kSub = 4;

/// The lens of the geometric-calibration tests (tests/support/truth_lens.h).
CameraModel lens() { return test::truth_lens(); }

const CalibrationTarget& target() {
    static const CalibrationTarget t = CalibrationTarget::parse("checkerboard:9x6:0.06");
    return t;
}

const std::vector<std::vector<float>>& frames() {
    static const std::vector<std::vector<float>> instance = [] {
        const CameraModel m = lens();
        // Normalised ray of every sub-sample, once: the same lens for every view.
        std::vector<Vec2> rays(static_cast<std::size_t>(kW * kSub) * kH * kSub);
        for (int y = 0; y < kH * kSub; ++y)
            for (int x = 0; x < kW * kSub; ++x)
                rays[static_cast<std::size_t>(y) * kW * kSub + static_cast<std::size_t>(x)] =
                    m.undistort(Vec2((x + 0.5) / kSub - 0.5, (y + 0.5) / kSub - 0.5));
        std::vector<std::vector<float>> out;
        std::mt19937 rng(3);
        std::normal_distribution<float> noise(0.0f, 2.0f);
        for (int v = 0; v < kViews; ++v) {
            const double tilt = deg_to_rad(20.0 + 4.0 * (v % 5)), axis = 2.0 * kPi * v / kViews;
            const Mat3 r =
                Eigen::AngleAxisd(tilt, Vec3(std::cos(axis), std::sin(axis), 0)).toRotationMatrix();
            const Vec3 centre(0.03 * std::cos(3 * axis), 0.02 * std::sin(2 * axis),
                              0.85 + 0.02 * (v % 3));
            const Vec3 normal = r.col(2), ex = r.col(0), ey = r.col(1);
            std::vector<float> frame(static_cast<std::size_t>(kW) * kH, 0.0f);
            for (std::size_t i = 0; i < rays.size(); ++i) {
                const Vec3 d(rays[i].x(), rays[i].y(), 1.0);
                const double s = normal.dot(centre) / normal.dot(d);
                const Vec3 p = s * d - centre;
                const double u = p.dot(ex) / 0.06 + 5.0, w = p.dot(ey) / 0.06 + 3.5;
                const bool hot = u > 0 && w > 0 && u < 10 && w < 7 &&
                                 (static_cast<int>(u) + static_cast<int>(w)) % 2 == 0;
                const std::size_t x = (i % (kW * kSub)) / kSub, y = (i / (kW * kSub)) / kSub;
                frame[y * kW + x] += hot ? 1.0f / (kSub * kSub) : 0.0f;
            }
            for (float& f : frame) f = 8000.0f + 60.0f * f + noise(rng);
            out.push_back(std::move(frame));
        }
        return out;
    }();
    return instance;
}

void BM_CopyOf20Frames(benchmark::State& state) {
    const auto& in = frames();
    std::vector<float> out(in.front().size());
    for (auto _ : state) {
        for (const auto& f : in) {
            std::memcpy(out.data(), f.data(), f.size() * sizeof(float));
            benchmark::DoNotOptimize(out.data());
            benchmark::ClobberMemory();
        }
    }
}
BENCHMARK(BM_CopyOf20Frames)->Unit(benchmark::kMillisecond);

std::vector<TargetView> found_views(const std::vector<std::optional<TargetView>>& detected) {
    std::vector<TargetView> views;
    for (const auto& v : detected)
        if (v) views.push_back(*v);
    return views;
}

void BM_Detect20Views(benchmark::State& state) {
    const auto& in = frames();
    for (auto _ : state) {
        const auto views = found_views(detect_target_views(in, kW, kH, target()));
        if (views.size() != kViews) state.SkipWithError("target not found in every view");
        benchmark::DoNotOptimize(views.data());
    }
}
BENCHMARK(BM_Detect20Views)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_DetectAndCalibrate20Views(benchmark::State& state) {
    const auto& in = frames();
    double fx = 0.0;
    for (auto _ : state) {
        const auto views = found_views(detect_target_views(in, kW, kH, target()));
        const auto result = calibrate_geometric(views, target(), kW, kH);
        fx = result.model.fx;
    }
    state.counters["fx_error_pct"] = 100.0 * std::abs(fx - lens().fx) / lens().fx;
}
BENCHMARK(BM_DetectAndCalibrate20Views)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
