#include "tirpol/calibration/microgrid_stokes.h"

#include <cmath>
#include <numbers>

#include "microgrid_frame_check.h"
#include "microgrid_single_pass.h"
#include "tirpol/core/error.h"
#include "tirpol/core/stokes.h"

namespace tirpol::calibration {

std::vector<float> microgrid_from_stokes(std::span<const float> s0, std::span<const float> s1,
                                         std::span<const float> s2, int width, int height,
                                         const MicrogridPattern& pattern) {
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    if (width <= 0 || height <= 0 || s0.size() != n || s1.size() != n || s2.size() != n)
        fail(
            "microgrid_from_stokes: Stokes planes of {}, {} and {} values for a {}×{} frame; "
            "expected {} each",
            s0.size(), s1.size(), s2.size(), width, height, n);
    std::array<double, 4> cos2{}, sin2{};
    for (std::size_t c = 0; c < 4; ++c) {
        const double theta = pattern.angles_deg()[c] * std::numbers::pi / 180.0;
        cos2[c] = std::cos(2.0 * theta);
        sin2[c] = std::sin(2.0 * theta);
    }
    std::vector<float> mosaic(n);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                  static_cast<std::size_t>(x);
            const std::size_t c = static_cast<std::size_t>((y & 1) * 2 + (x & 1));
            mosaic[i] = static_cast<float>(0.5 * (s0[i] + s1[i] * cos2[c] + s2[i] * sin2[c]));
        }
    return mosaic;
}

namespace {

/// The analyzer model of the options, or ideal analyzers at the pattern's angles; checked against
/// the pattern.
AnalyzerModel analyzer_model(const MicrogridPattern& pattern,
                             const MicrogridReductionOptions& options) {
    AnalyzerModel model = options.analyzer;
    if (model.positions.empty())
        return AnalyzerModel::ideal({pattern.angles_deg().begin(), pattern.angles_deg().end()});
    if (model.positions.size() != 4)
        fail("{}: the analyzer model has {} positions; a microgrid has 4 ({})", options.source,
             model.positions.size(), pattern.text());
    for (const auto& position : model.positions) pattern.cell_of(position.nominal_angle_deg);
    return model;
}

void write_microgrid_attributes(Image& stokes, const MicrogridPattern& pattern,
                                DemosaicMethod method) {
    pattern.write_to(stokes.attributes());
    stokes.attributes()["demosaic_method"] = std::string(demosaic_method_name(method));
    stokes.attributes()["demosaic_reference"] = std::string(demosaic_method_reference(method));
}

Image reduce_in_two_steps(std::span<const float> mosaic, int width, int height,
                          const MicrogridPattern& pattern, const AnalyzerModel& model,
                          const MicrogridReductionOptions& options) {
    const DemosaicedFrame frame =
        demosaic_microgrid(mosaic, width, height, pattern, options.method, options.source);
    std::vector<AnalyzerPlanes> planes;
    for (std::size_t c = 0; c < 4; ++c)
        planes.push_back(
            {frame.angles_deg[c],
             frame.planes[c],
             {},
             fmt::format("{} ({:g}° demosaiced)", options.source, frame.angles_deg[c])});
    return reduce_stokes(planes, frame.width, frame.height, model, nullptr, options.reduction);
}

bool single_pass(const MicrogridReductionOptions& options) {
    return options.single_pass && !options.reduction.include_slar;
}

}  // namespace

Image reduce_microgrid(std::span<const float> mosaic, int width, int height,
                       const MicrogridPattern& pattern, const MicrogridReductionOptions& options) {
    const AnalyzerModel model = analyzer_model(pattern, options);
    Image stokes;
    if (single_pass(options)) {
        detail::check_microgrid_frame(mosaic, width, height, options.source);
        stokes = detail::reduce_microgrid_single_pass(mosaic, width, height, pattern, model,
                                                      options.method, options.reduction);
    } else {
        stokes = reduce_in_two_steps(mosaic, width, height, pattern, model, options);
    }
    write_microgrid_attributes(stokes, pattern, options.method);
    return stokes;
}

Image reduce_microgrid(std::span<const std::uint16_t> mosaic, int width, int height,
                       const MicrogridPattern& pattern, const MicrogridReductionOptions& options) {
    const AnalyzerModel model = analyzer_model(pattern, options);
    detail::check_microgrid_size(mosaic.size(), width, height, options.source);
    Image stokes;
    if (single_pass(options)) {
        stokes = detail::reduce_microgrid_single_pass(mosaic, width, height, pattern, model,
                                                      options.method, options.reduction);
    } else {
        const std::vector<float> as_float(mosaic.begin(), mosaic.end());
        stokes = reduce_in_two_steps(as_float, width, height, pattern, model, options);
    }
    write_microgrid_attributes(stokes, pattern, options.method);
    return stokes;
}

}  // namespace tirpol::calibration
