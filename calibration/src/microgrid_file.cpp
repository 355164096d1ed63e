#include "microgrid_file.h"

#include <utility>

#include "tirpol/calibration/stokes_reduction.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"

namespace tirpol::calibration {

MicrogridFileReduction reduce_microgrid_file(const std::filesystem::path& input,
                                             const std::optional<MicrogridPattern>& pattern,
                                             MicrogridReductionOptions options,
                                             const std::string& exr_channel) {
    const Image frame = read_raw_image(input, "counts", exr_channel);
    const Attributes& header = frame.attributes();
    std::optional<MicrogridPattern> recorded;
    if (header.count("microgrid_pattern_deg")) {
        try {
            recorded = MicrogridPattern::from_attributes(header);
        } catch (const Error& e) {
            fail("{}: {}", input.string(), e.what());
        }
    }
    if (pattern && recorded && pattern->angles_deg() != recorded->angles_deg())
        fail(
            "{}: the header records the microgrid pattern {} but {} was given; expected the same "
            "pattern (or give none "
            "to use the recorded one)",
            input.string(), recorded->text(), pattern->text());
    if (!pattern && !recorded)
        fail(
            "{}: no microgrid pattern given and none recorded in the file (attribute "
            "microgrid_pattern_deg); expected "
            "the four angles of the 2×2 cell, e.g. 90,45,135,0 for a Sony IMX250MZR",
            input.string());
    const MicrogridPattern& used = pattern ? *pattern : *recorded;
    options.reduction.units =
        read_stokes_image_header(frame, input.string()).units.value_or("counts");
    options.source = input.string();
    Image stokes =
        reduce_microgrid(frame.channel("counts"), frame.width(), frame.height(), used, options);
    stokes.attributes()["source_file"] = input.string();
    if (const auto bits = header.find("source_depth_bits"); bits != header.end())
        stokes.attributes()["source_depth_bits"] = bits->second;
    const int unrealizable = stokes_reduction_record(stokes).unrealizable_pixels;
    return {std::move(stokes), used, options.reduction.units, unrealizable};
}

}  // namespace tirpol::calibration
