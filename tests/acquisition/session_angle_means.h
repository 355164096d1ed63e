#pragma once
// The pixel mean of each polarizer angle's frame in one repeat of a capture session: what the FFC
// tests turn into S1 = I0 − I90 and S2 = I45 − I135.

#include <cmath>
#include <filesystem>
#include <map>

#include "tirpol/core/session.h"

namespace tirpol::test {

/// Requested angle (deg, rounded) → pixel-mean counts of that angle's record in `repeat`.
inline std::map<int, double> polarizer_means_by_angle(const std::filesystem::path& dir,
                                                      int repeat) {
    const SessionManifest m = read_session(dir);
    std::map<int, double> mean;
    for (const auto& r : m.records) {
        if (r.kind != RecordKind::Polarizer || r.repeat != repeat) continue;
        const Image image = read_session_frame(dir, m, r);
        const auto& counts = image.channel("counts");
        double sum = 0.0;
        for (float c : counts) sum += c;
        mean[static_cast<int>(std::lround(r.angle_deg_requested))] =
            sum / static_cast<double>(counts.size());
    }
    return mean;
}

}  // namespace tirpol::test
