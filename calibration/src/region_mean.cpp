#include "tirpol/calibration/emissivity_extraction.h"

namespace tirpol::calibration {

RegionMean region_mean(const Image& image, const std::string& channel, const PixelRect& rect,
                       const std::string& what) {
    if (rect.x < 0 || rect.y < 0 || rect.x + rect.width > image.width() ||
        rect.y + rect.height > image.height())
        fail("{}: rectangle [{}, {}, {}, {}] is outside the {}×{} image", what, rect.x, rect.y,
             rect.width, rect.height, image.width(), image.height());
    const auto& plane = image.channel(channel);
    return region_mean_of(rect, what, channel,
                          [&](int x, int y) { return plane[image.index(x, y)]; });
}

}  // namespace tirpol::calibration
