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
    struct Look {
        const char* channel;
        const char* units;
    };
    for (const Look& look :
         {Look{"S0", "W/(m²·sr)"}, Look{"S1", "W/(m²·sr)"}, Look{"S2", "W/(m²·sr)"},
          Look{"DoLP", ""}, Look{"AoP", "deg"}, Look{"temperature_k", "K"}}) {
        if (!image.has_channel(look.channel)) continue;
        QuicklookOptions q;
        q.colormap = default_colormap(look.channel);
        q.title = look.channel;
        q.units = look.units;
        if (std::string(look.channel) == "AoP") {
            q.vmin = 0.0;
            q.vmax = 180.0;
        }
        written.push_back(out_dir / (stem + "_" + look.channel + ".png"));
        write_quicklook(written.back(), image.channel(look.channel), image.width(), image.height(),
                        q);
    }
    return written;
}

}  // namespace tirpol::simulation
