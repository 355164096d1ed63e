#include "tirpol/core/raster_io.h"

#include <algorithm>
#include <cctype>
#include <opencv2/imgcodecs.hpp>

#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"

namespace tirpol {

Image read_raw_image(const std::filesystem::path& path, const std::string& channel_name, const std::string& exr_channel) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".exr") {
        const Image exr = read_exr(path);
        if (!exr.has_channel(exr_channel)) fail("{}: no channel '{}' (raw counts expected)", path.string(), exr_channel);
        Image out(exr.width(), exr.height());
        out.set_channel(channel_name, exr.channel(exr_channel));
        out.attributes() = exr.attributes();
        return out;
    }
    if (ext != ".png" && ext != ".tif" && ext != ".tiff")
        fail("{}: unsupported raw image type '{}'; expected .exr, .png or .tif/.tiff", path.string(), ext);
    if (!std::filesystem::exists(path)) fail("{}: no such file", path.string());
    const cv::Mat m = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
    if (m.empty()) fail("{}: cannot be decoded as {} (truncated or corrupt?)", path.string(), ext);
    if (m.channels() != 1) fail("{}: has {} channels; expected a single-channel raw image", path.string(), m.channels());
    cv::Mat f;
    m.convertTo(f, CV_32F);
    Image out(f.cols, f.rows);
    std::vector<float> plane(static_cast<std::size_t>(f.cols) * static_cast<std::size_t>(f.rows));
    for (int y = 0; y < f.rows; ++y) std::copy_n(f.ptr<float>(y), f.cols, plane.begin() + static_cast<std::ptrdiff_t>(y) * f.cols);
    out.set_channel(channel_name, std::move(plane));
    out.attributes()["source_depth_bits"] = static_cast<int>(m.elemSize1() * 8);
    return out;
}

}  // namespace tirpol
