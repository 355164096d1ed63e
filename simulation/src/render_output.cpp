#include "tirpol/simulation/render_output.h"

#include "tirpol/core/exr_io.h"
#include "tirpol/core/quicklook.h"

namespace tirpol::simulation {

std::vector<std::filesystem::path> write_render_outputs(const std::filesystem::path& out_dir,
                                                        const std::string& stem,
                                                        const Image& image) {
    std::filesystem::create_directories(out_dir);
    std::vector<std::filesystem::path> written;
    written.push_back(out_dir / (stem + ".exr"));
    write_exr(written.back(), image);
    for (const char* channel : {"S0", "S1", "S2", "DoLP", "AoP", "temperature_k"}) {
        if (!image.has_channel(channel)) continue;
        const QuicklookOptions q = channel_quicklook_options(channel);
        written.push_back(out_dir / (stem + "_" + channel + ".png"));
        write_quicklook(written.back(), image.channel(channel), image.width(), image.height(), q);
    }
    return written;
}

}  // namespace tirpol::simulation
