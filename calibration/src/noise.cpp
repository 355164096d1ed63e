#include "tirpol/calibration/noise.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tirpol/core/error.h"
#include "validate.h"

namespace tirpol::calibration {

void validate_stack(const FrameStack& stack, const char* source) {
    if (stack.frames.size() < 2)
        fail("{}: {} frame(s); temporal noise needs at least 2 frames", source,
             stack.frames.size());
    const std::size_t n =
        static_cast<std::size_t>(stack.width) * static_cast<std::size_t>(stack.height);
    for (std::size_t t = 0; t < stack.frames.size(); ++t)
        detail::check_plane(stack.frames[t], n, fmt::format("{} frame {}", source, t), stack.width,
                            stack.height);
}

const char* to_string(NoiseConvention convention) {
    return convention == NoiseConvention::Sample ? "sample (N-1, as pyradi ry3dnoise)"
                                                 : "population (N)";
}

ThreeDNoise three_d_noise(const FrameStack& stack, NoiseConvention convention) {
    const std::size_t nt = stack.frames.size(), nv = static_cast<std::size_t>(stack.height),
                      nh = static_cast<std::size_t>(stack.width);
    // Directional means: over (v,h) per t, over (t,h) per v, over (t,v) per h, and the pairwise
    // ones.
    std::vector<double> m_t(nt, 0.0), m_v(nv, 0.0), m_h(nh, 0.0), m_tv(nt * nv, 0.0),
        m_th(nt * nh, 0.0), m_vh(nv * nh, 0.0);
    double s = 0.0;
    for (std::size_t t = 0; t < nt; ++t)
        for (std::size_t v = 0; v < nv; ++v)
            for (std::size_t h = 0; h < nh; ++h) {
                const double u = stack.frames[t][v * nh + h];
                s += u;
                m_t[t] += u;
                m_v[v] += u;
                m_h[h] += u;
                m_tv[t * nv + v] += u;
                m_th[t * nh + h] += u;
                m_vh[v * nh + h] += u;
            }
    const double n = static_cast<double>(nt * nv * nh);
    s /= n;
    for (auto& x : m_t) x /= static_cast<double>(nv * nh);
    for (auto& x : m_v) x /= static_cast<double>(nt * nh);
    for (auto& x : m_h) x /= static_cast<double>(nt * nv);
    for (auto& x : m_tv) x /= static_cast<double>(nh);
    for (auto& x : m_th) x /= static_cast<double>(nv);
    for (auto& x : m_vh) x /= static_cast<double>(nt);

    auto n_t = [&](std::size_t t) { return m_t[t] - s; };
    auto n_v = [&](std::size_t v) { return m_v[v] - s; };
    auto n_h = [&](std::size_t h) { return m_h[h] - s; };
    auto n_tv = [&](std::size_t t, std::size_t v) {
        return m_tv[t * nv + v] - s - n_t(t) - n_v(v);
    };
    auto n_th = [&](std::size_t t, std::size_t h) {
        return m_th[t * nh + h] - s - n_t(t) - n_h(h);
    };
    auto n_vh = [&](std::size_t v, std::size_t h) {
        return m_vh[v * nh + h] - s - n_v(v) - n_h(h);
    };

    double ss_t = 0, ss_v = 0, ss_h = 0, ss_tv = 0, ss_th = 0, ss_vh = 0, ss_tvh = 0;
    for (std::size_t t = 0; t < nt; ++t) ss_t += n_t(t) * n_t(t);
    for (std::size_t v = 0; v < nv; ++v) ss_v += n_v(v) * n_v(v);
    for (std::size_t h = 0; h < nh; ++h) ss_h += n_h(h) * n_h(h);
    for (std::size_t t = 0; t < nt; ++t)
        for (std::size_t v = 0; v < nv; ++v) ss_tv += n_tv(t, v) * n_tv(t, v);
    for (std::size_t t = 0; t < nt; ++t)
        for (std::size_t h = 0; h < nh; ++h) ss_th += n_th(t, h) * n_th(t, h);
    for (std::size_t v = 0; v < nv; ++v)
        for (std::size_t h = 0; h < nh; ++h) ss_vh += n_vh(v, h) * n_vh(v, h);
    for (std::size_t t = 0; t < nt; ++t)
        for (std::size_t v = 0; v < nv; ++v)
            for (std::size_t h = 0; h < nh; ++h) {
                const double r = stack.frames[t][v * nh + h] - s - n_t(t) - n_v(v) - n_h(h) -
                                 n_tv(t, v) - n_th(t, h) - n_vh(v, h);
                ss_tvh += r * r;
            }
    // Sample convention: one degree of freedom less per component (a 1-row or 1-column image has
    // nothing to spread over; its component is 0 either way, so max(1, …) only avoids 0/0).
    const double dof = convention == NoiseConvention::Sample ? 1.0 : 0.0;
    auto sigma = [dof](double ss, double count) {
        return std::sqrt(ss / std::max(1.0, count - dof));
    };
    ThreeDNoise out;
    out.mean = s;
    out.sigma_t = sigma(ss_t, static_cast<double>(nt));
    out.sigma_v = sigma(ss_v, static_cast<double>(nv));
    out.sigma_h = sigma(ss_h, static_cast<double>(nh));
    out.sigma_tv = sigma(ss_tv, static_cast<double>(nt * nv));
    out.sigma_th = sigma(ss_th, static_cast<double>(nt * nh));
    out.sigma_vh = sigma(ss_vh, static_cast<double>(nv * nh));
    out.sigma_tvh = sigma(ss_tvh, n);
    out.sigma_total = std::sqrt(out.sigma_t * out.sigma_t + out.sigma_v * out.sigma_v +
                                out.sigma_h * out.sigma_h + out.sigma_tv * out.sigma_tv +
                                out.sigma_th * out.sigma_th + out.sigma_vh * out.sigma_vh +
                                out.sigma_tvh * out.sigma_tvh);
    return out;
}

std::vector<float> temporal_noise(const FrameStack& stack) {
    const std::size_t n = stack.frames.front().size();
    const double nt = static_cast<double>(stack.frames.size());
    std::vector<float> sigma(n);
    for (std::size_t i = 0; i < n; ++i) {
        double mean = 0.0;
        for (const auto& f : stack.frames) mean += f[i];
        mean /= nt;
        double ss = 0.0;
        for (const auto& f : stack.frames) ss += (f[i] - mean) * (f[i] - mean);
        sigma[i] = static_cast<float>(std::sqrt(ss / (nt - 1.0)));
    }
    return sigma;
}

std::vector<float> nedt_map(const std::vector<float>& temporal_sigma,
                            const std::vector<float>& responsivity_per_k) {
    if (temporal_sigma.size() != responsivity_per_k.size())
        fail("NEDT: noise map has {} pixels, responsivity map {}; expected the same size",
             temporal_sigma.size(), responsivity_per_k.size());
    std::vector<float> nedt(temporal_sigma.size());
    for (std::size_t i = 0; i < nedt.size(); ++i)
        nedt[i] = responsivity_per_k[i] > 0.0f ? temporal_sigma[i] / responsivity_per_k[i]
                                               : std::numeric_limits<float>::quiet_NaN();
    return nedt;
}

double finite_median(std::vector<float> values) {
    values.erase(
        std::remove_if(values.begin(), values.end(), [](float v) { return !std::isfinite(v); }),
        values.end());
    if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
    const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), mid, values.end());
    return *mid;
}

std::vector<AveragingPoint> nedt_vs_averaging(const FrameStack& stack,
                                              const std::vector<float>& responsivity_per_k) {
    std::vector<AveragingPoint> points;
    double nedt1 = 0.0;
    for (int n = 1; static_cast<int>(stack.frames.size()) / n >= 4; n *= 2) {
        FrameStack means{stack.width, stack.height, {}};
        const std::size_t groups = stack.frames.size() / static_cast<std::size_t>(n);
        for (std::size_t g = 0; g < groups; ++g) {
            std::vector<float> mean(stack.frames.front().size(), 0.0f);
            for (int k = 0; k < n; ++k) {
                const auto& f =
                    stack.frames[g * static_cast<std::size_t>(n) + static_cast<std::size_t>(k)];
                for (std::size_t i = 0; i < mean.size(); ++i)
                    mean[i] += f[i] / static_cast<float>(n);
            }
            means.frames.push_back(std::move(mean));
        }
        const double nedt = finite_median(nedt_map(temporal_noise(means), responsivity_per_k));
        if (n == 1) nedt1 = nedt;
        points.push_back({n, nedt, nedt1 / std::sqrt(static_cast<double>(n))});
    }
    return points;
}

}  // namespace tirpol::calibration
